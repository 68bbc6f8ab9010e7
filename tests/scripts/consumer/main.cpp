// Checks a pipeline with the installed library, as `terraweave validate` does.
#include <cstdio>
#include <exception>

#include "pipeline/config.hpp"
#include "pipeline/run.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  try {
    const tw::PipelineConfig config = tw::load_pipeline(argv[1]);
    tw::RunOptions options;
    options.write_outputs = false;
    const tw::RunReport report = tw::run_pipeline(config, options);
    std::printf("grid %d x %d, %zu warnings\n", report.grid.width, report.grid.height,
                report.warnings.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
