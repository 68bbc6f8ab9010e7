#pragma once
// Runs a pipeline: ingest -> ribbons -> avoidance -> synthesis -> terrain -> layers, each stage
// timed, every output staged in one OutputFolder and committed at the very end (a run that
// fails writes nothing; a killed run leaves the previous outputs in place).
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/config.hpp"
#include "pipeline/method_report.hpp"

namespace tw {

// The most worker threads a run accepts (more is a typo, and TBB would start them all).
inline constexpr int kMaxThreads = 1024;

struct RunOptions {
  std::optional<std::filesystem::path> output_dir;  // replaces output.dir
  std::optional<std::string> backend;               // replaces backend (cpu | opencl | auto)
  int threads = 0;                                  // 0 = every core; at most kMaxThreads
  bool write_outputs = true;   // false: read and check every input, write nothing (validate)
  bool strict = false;         // any warning fails the run (or config.strict)
  bool allow_network = false;  // inputs may be URLs (/vsicurl/...), CRSs may be fetched
  // `--cache DIR` (docs/cache.md): reuse the syntheses and tiles whose inputs are unchanged.
  std::optional<std::filesystem::path> cache_dir;
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
  Structure structure = Structure::ground;
  int layer = 0;
  // A bridge's or tunnel's deck height at its start and end (metres; straight between).
  std::optional<std::array<double, 2>> deck_m;
  // Conformance (docs/terrain.md): how far the line was moved onto the DEM (0: as drawn), and
  // the largest cut (below the terrain) and fill (above it) of its centreline profile.
  double moved_max_m = 0.0, moved_mean_m = 0.0;
  double cut_max_m = 0.0, fill_max_m = 0.0;
  // The steepest grade of its profile (rise over run, e.g. 0.08 = 8 %; 0 for ridges).
  double grade_max = 0.0;
};

struct FeatureClassReport {
  std::string name;
  FeatureKind kind = FeatureKind::road;
  std::string source;  // path:layer (a grown class: its element set)
  double delta_m = 0.0;
  std::vector<FeatureReport> features;  // in reading order (a multi-part FID repeats)
  double ingest_seconds = 0.0;
};

// One tile of the output (docs/tiles.md): its place, how long its render and write took, and
// an xxHash64 of its layers' bytes (every band's float pixels over its halo window, in layer
// and channel order) that equal renders share.
struct TileReport {
  int index = 0, ix = 0, iy = 0;
  Window window;       // core
  Window halo_window;  // what its files hold
  double seconds = 0.0;
  std::uint64_t xxh64 = 0;
  std::optional<CacheStatus> cache;  // tiled runs: rendered or copied from `--cache`, and why
};

struct TilesReport {
  int size = 0;  // 0: untiled, one tile
  int overlap = 0;
  std::vector<TileReport> tiles;
};

// One file of the manifest (report.json `inputs` and `outputs`).
struct FileRecord {
  std::string role;  // heightfield, vector, exemplar; outputs: their name in the folder
  std::string path;  // as the pipeline named it (inputs) or relative to the folder (outputs)
  std::uintmax_t bytes = 0;
  std::string xxh3_128;  // hex, core/file_hash.hpp
};

// The lowest and highest height that is not nodata (absent: every cell is nodata).
using HeightRange = std::optional<std::array<float, 2>>;

struct RunReport {
  GridSpec grid;
  std::string crs_wkt;
  std::string heightfield;  // path or generated:seed=N
  std::uint64_t seed = 0;
  std::vector<StageTiming> stages;
  std::vector<FeatureClassReport> classes;
  // What the methods report of their classes, features and the run (method_report<T>): one
  // part per method that reports, of its own type; the method writes it into report.json.
  std::vector<MethodReportPart> method_parts;
  std::vector<std::filesystem::path> outputs;  // committed files (report.json last)
  std::int64_t forbidden_pixels = 0;           // in the avoidance layer
  double total_seconds = 0.0;
  std::vector<Warning> warnings;  // in the order they were raised (report.json `warnings`)
  TilesReport tiles;

  // The manifest (docs/cli.md, "report.json"): what was read and written, and the heights.
  std::vector<FileRecord> inputs;        // every file the run read, hashed
  std::vector<FileRecord> output_files;  // every file written but report.json, hashed
  HeightRange input_height, output_height;
  std::string started_utc;  // ISO 8601, e.g. 2026-12-01T23:58:02Z
};

// Throws tw::Error naming the file, layer, FID or key of the first bad input; under strict
// (options or config) also when the run raised any warning, before anything is written.
RunReport run_pipeline(const PipelineConfig& config, const RunOptions& options = {});

}  // namespace tw
