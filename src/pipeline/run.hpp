#pragma once
// Runs a pipeline: ingest -> ribbons -> avoidance -> terrain -> layers, each stage timed,
// every output staged in one OutputTransaction and committed at the very end (a run that
// fails writes nothing; a killed run leaves the previous outputs in place).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "pipeline/config.hpp"

namespace tw {

struct RunOptions {
  std::optional<std::filesystem::path> output_dir;  // replaces output.dir
  std::optional<std::string> backend;               // replaces backend (cpu | opencl | auto)
  int threads = 0;                                  // 0 = every core
  bool write_outputs = true;  // false: read and check every input, write nothing (validate)
};

struct StageTiming {
  std::string stage;  // ingest, ribbons, avoidance, synthesis, terrain, layers
  double seconds = 0.0;
};

struct FeatureReport {
  std::int64_t fid = 0;
  double length_m = 0.0;  // in the grid's metric CRS
  double width_m = 0.0;
  int pieces = 0;  // ribbon pieces of length delta (0 when shorter than one piece)
};

struct FeatureClassReport {
  std::string name;
  FeatureKind kind = FeatureKind::road;
  std::string source;  // path:layer
  double delta_m = 0.0;
  std::vector<FeatureReport> features;  // in reading order (a multi-part FID repeats)
  double ingest_seconds = 0.0;
};

struct RunReport {
  GridSpec grid;
  std::string crs_wkt;
  std::string heightfield;  // path or generated:seed=N
  std::uint64_t seed = 0;
  std::vector<StageTiming> stages;
  std::vector<FeatureClassReport> classes;
  std::vector<std::filesystem::path> outputs;  // committed files (report.json last)
  std::int64_t forbidden_pixels = 0;           // in the avoidance layer
  double total_seconds = 0.0;
};

// Throws tw::Error naming the file, layer, FID or key of the first bad input.
RunReport run_pipeline(const PipelineConfig& config, const RunOptions& options = {});

}  // namespace tw
