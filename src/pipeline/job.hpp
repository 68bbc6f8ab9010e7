#pragma once
// A run split into independent processes (docs/distributed.md): `terraweave plan` plans the
// world once and writes the plan and its task list; `terraweave render-tile` renders one tile
// (on any machine that shares the output folder); `terraweave finish` gathers the tiles into
// the output folder and commits it. The same bytes as `terraweave run` of the pipeline.
//
// Where the files are, in the output folder <out> (the plan folder is <out>/.terraweave/plan):
//   plan/plan.json, tasks.json, objects/   the plan (pipeline/plan_io.hpp)
//   plan/job.json                          the pipeline file, its --set overrides and the
//                                          folder they resolve against (for finish's report)
//   plan/tiles-<plan>/tiles/<stem>.<ext>   a rendered tile's files, each written to a
//                                          temporary and renamed: complete or absent
//   plan/results-<plan>/tile-<i>.json      written last by render-tile: the tile's files with
//                                          their sizes and XXH3-128 hashes, and its timings
// Names carry the plan's hash, so a worker still running for an earlier plan never writes
// where the current one looks. finish holds the output folder's lock (core/output_folder.hpp),
// checks every result against the plan and every file against its hash, hard-links the tile
// files into its staging folder (copies when it cannot link), writes the mosaics, placements,
// preview and report.json, commits, and only then deletes the plan's tile files.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/run.hpp"

namespace tw {

struct PlanJobOptions {
  std::filesystem::path output_dir;    // the shared output folder
  std::optional<std::string> backend;  // replaces backend (cpu | opencl | auto)
  std::vector<std::string> overrides;  // the --set assignments, as given (--seed N as seed=N)
  // --vars: the variables file the pipeline was read with ("" = none); every task reads the
  // pipeline with it again (job.json), as with the overrides.
  std::filesystem::path variables;
  bool strict = false;                 // any warning fails the plan
  bool allow_network = false;
  // --cache: syntheses and tiles reused from there and stored there (docs/cache.md); absent:
  // the pipeline's cache key, or none. Every task of the plan uses it (job.json).
  std::optional<std::filesystem::path> cache_dir;
  // --synthesis tasks: the plan leaves every synthesis to a task (pipeline/synthesis_job.hpp).
  bool synthesis_tasks = false;
};

struct PlannedJob {
  std::filesystem::path plan_dir;
  std::string plan;  // its hash
  std::size_t tiles = 0;
  std::size_t warnings = 0;
  // Syntheses left to synth-feature and complete-plan (0: the plan is complete).
  std::size_t syntheses = 0;
};

// Plans the world and writes <out>/.terraweave/plan (replacing an earlier plan there).
PlannedJob plan_job(const PipelineConfig& config, const PlanJobOptions& options);

// `path` itself when it holds plan.json, else <path>/.terraweave/plan when that does.
// Throws tw::Error naming `path` otherwise.
std::filesystem::path find_plan_dir(const std::filesystem::path& path);

struct TileJobResult {
  int tile = 0;
  std::vector<std::filesystem::path> files;  // relative to the output folder
  double seconds = 0.0;
};

// Renders tile `tile` (its index in tasks.json) of the plan in `plan_dir`. A rerun (a worker
// lost, a task retried anywhere) writes the same bytes under the same names.
// Test hook: TERRAWEAVE_TEST_PAUSE_AT=render-tile pauses before the tile is rendered
// (core/output_folder.hpp, test_pause_point).
TileJobResult render_job_tile(const std::filesystem::path& plan_dir, int tile);

// Gathers every tile of the plan into its output folder and commits it. Throws tw::Error
// naming the first tile that is missing, belongs to another plan, or whose file does not match
// its recorded hash (render it again).
RunReport finish_job(const std::filesystem::path& plan_dir);

}  // namespace tw
