#pragma once
// `terraweave diff RUN_A RUN_B` (docs/cli.md): what changed between two runs, from their
// manifests (report.json) and their layers, band by band.
#include <filesystem>
#include <string>
#include <vector>

#include "layers/compare.hpp"

namespace tw {

struct LayerFileDifference {
  std::string file;  // e.g. height.tif, as named in report.json `outputs`
  RasterDifference raster;
};

struct RunDifference {
  std::vector<LayerFileDifference> layers;  // raster outputs in both runs that differ
  // Other outputs: "name: only in A", "name: only in B", "name: contents differ".
  std::vector<std::string> files;
  // The manifests without `timings` and `outputs`, as "/json/pointer: old -> new" (a key
  // only in one: "-> new" or "old ->"); inputs, configuration, features, heights, warnings.
  std::vector<std::string> manifest;
  bool identical() const { return layers.empty() && files.empty() && manifest.empty(); }
};

// Throws tw::Error when a folder holds no report.json of schema 2 or later, or a file cannot
// be read. `verify`: first every file of both runs is checked against its run's report.json
// (pipeline/run_layers.hpp, verify_run_files: an error names a changed file). Files are
// compared by their hashes as they are now (never only as recorded: a truncated file differs);
// pixels are read only where the two files' hashes differ.
RunDifference diff_runs(const std::filesystem::path& run_a, const std::filesystem::path& run_b,
                        bool verify = true);

// The lines `terraweave diff` prints (one "identical" line when nothing differs).
std::vector<std::string> describe(const RunDifference& difference);

}  // namespace tw
