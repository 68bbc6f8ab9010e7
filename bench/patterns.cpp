// Pattern synthesis inside the pipeline (issue #4). Each case runs in a child process so that
// its peak memory (getrusage ru_maxrss) is its own. Prints time per stage, per-feature synthesis
// numbers and peak RSS; never fails on time.
//   bench_patterns demo            the demo world (pipelines/demo.yaml), cpu and opencl
//   bench_patterns long            a 50 km road at delta 5 m (10 000 pieces) with a small
//                                  exemplar, on a 4096^2 world with 100 km of features
//   bench_patterns                 both
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/log.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/run.hpp"

namespace fs = std::filesystem;

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

void print_report(const std::string& name, const tw::RunReport& report) {
  std::printf("%s: grid %d x %d, total %.2f s, peak RSS %.0f MB, violations %lld\n", name.c_str(),
              report.grid.width, report.grid.height, report.total_seconds, peak_rss_mb(),
              static_cast<long long>(tw::detail::pattern_violations(report)));
  for (const auto& s : report.stages) std::printf("  %-10s %8.2f s\n", s.stage.c_str(), s.seconds);
  for (std::size_t ci = 0; ci < report.classes.size(); ++ci) {
    const auto& c = report.classes[ci];
    int pieces = 0, features = 0;
    double length = 0, synth = 0, valid = 0, seam = 0, stitched = 0;
    for (std::size_t i = 0; i < c.features.size(); ++i) {
      const auto& f = c.features[i];
      length += f.length_m;
      const tw::FeatureSynthesisReport* s = tw::detail::synthesis_report(report, ci, i);
      if (!s) continue;
      ++features;
      pieces += f.pieces;
      synth += s->avoidance_seconds + s->synthesis_seconds + s->render_seconds;
      valid += s->mean_valid_positions * f.pieces;
      seam += s->mean_seam_cost * f.pieces;
      stitched += s->mean_seam_cost_stitched * f.pieces;
    }
    std::printf("  class %-8s %6.1f km", c.name.c_str(), length / 1000.0);
    if (features > 0) {
      std::printf(
          ", %d features synthesized, %d pieces, %.0f valid/piece, seam %.2f -> %.2f, %.2f s",
          features, pieces, valid / pieces, seam / pieces, stitched / pieces, synth);
    }
    std::printf("\n");
  }
  std::fflush(stdout);
}

void demo(const std::string& backend) {
  const fs::path out = fs::temp_directory_path() / ("tw_bench_patterns_demo_" + backend);
  const tw::PipelineConfig config = tw::load_pipeline(
      fs::path(TERRAWEAVE_SOURCE_DIR) / "pipelines/demo.yaml", {{"output.dir", out.string()}});
  tw::RunOptions options;
  options.backend = backend;
  print_report("demo, backend " + backend, tw::run_pipeline(config, options));
  fs::remove_all(out);
}

// A 50 km road meandering west to east (y = 300 sin(x / 2 km)) and two 25 km rivers.
void long_road(const std::string& backend) {
  const fs::path dir = fs::temp_directory_path() / ("tw_bench_patterns_long_" + backend);
  fs::remove_all(dir);
  fs::create_directories(dir);
  GDALAllRegister();
  {
    std::ofstream geojson(dir / "lines.geojson");
    geojson
        << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:32631"}}, "features": [)";
    auto line = [&](int fid, const std::string& kind, auto point, double x0, double x1) {
      geojson << (fid > 1 ? "," : "") << R"({"type": "Feature", "id": )" << fid
              << R"(, "properties": {"kind": ")" << kind
              << R"("}, "geometry": {"type": "LineString", "coordinates": [)";
      bool first = true;
      for (double x = x0; x <= x1; x += 50.0) {
        const auto [px, py] = point(x);
        geojson << (first ? "" : ",") << "[" << px << "," << py << "]";
        first = false;
      }
      geojson << "]}}";
    };
    const double ox = 500000.0, oy = 5000000.0;  // north-west corner
    line(
        1, "road",
        [&](double x) {
          return std::pair{ox + x, oy - 25600.0 + 300.0 * std::sin(x / 2000.0)};
        },
        600.0, 50600.0);
    line(
        2, "river",
        [&](double x) {
          return std::pair{ox + x, oy - 10000.0 + 500.0 * std::sin(x / 3000.0)};
        },
        600.0, 25600.0);
    line(
        3, "river",
        [&](double x) {
          return std::pair{ox + x, oy - 40000.0 + 500.0 * std::cos(x / 2500.0)};
        },
        20000.0, 45000.0);
    geojson << "]}\n";
  }
  // A small exemplar: the first 80 columns of the cobble edging (and its height).
  const fs::path exemplars = fs::path(TERRAWEAVE_SOURCE_DIR) / "samples/exemplars";
  for (const auto& [src, dst, format] :
       {std::tuple{exemplars / "cobble_edging_200x56.png", dir / "cobble.png", "PNG"},
        std::tuple{exemplars / "cobble_edging_200x56_height.tif", dir / "cobble_height.tif",
                   "GTiff"}}) {
    GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
    const char* args[] = {"-of", format, "-srcwin", "0", "0", "80", "56", nullptr};
    GDALTranslateOptions* o = GDALTranslateOptionsNew(const_cast<char**>(args), nullptr);
    GDALClose(GDALTranslate(dst.c_str(), in, o, nullptr));
    GDALTranslateOptionsFree(o);
    GDALClose(in);
  }
  std::ofstream(dir / "long.yaml") << R"(version: 1
seed: 3
generate: { width: 4096, height: 4096, pixel_size: 12.5 }
output: { dir: out, geotiff: false, preview: false }
synthesis_resolution: 2
features:
  rivers: { source: lines.geojson, where: "kind = 'river'", kind: river, width: 12 }
  roads:
    source: lines.geojson
    where: "kind = 'road'"
    kind: road
    width: 8
    synthesis: { exemplar: cobble.png, width: 8, scale: 6, delta: 5 }
)";
  tw::RunOptions options;
  options.backend = backend;
  const tw::PipelineConfig config = tw::load_pipeline(dir / "long.yaml");
  print_report("4096^2 world, 50 km road at delta 5 m, backend " + backend,
               tw::run_pipeline(config, options));
  fs::remove_all(dir);
}

// Runs `body` in a child process (its own peak RSS).
void in_child(void (*body)(const std::string&), const std::string& backend) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    try {
      body(backend);
    } catch (const std::exception& e) {
      std::printf("  failed: %s\n", e.what());
      std::fflush(stdout);
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  const std::vector<std::string> backends =
      argc > 2 ? std::vector<std::string>{argv[2]} : std::vector<std::string>{"cpu", "opencl"};
  for (const std::string& backend : backends) {
    if (which == "all" || which == "demo") in_child(demo, backend);
    if (which == "all" || which == "long") in_child(long_road, backend);
  }
  return 0;
}
