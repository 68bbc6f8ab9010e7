#pragma once
// What `terraweave finish` writes besides the tiles (pipeline/job.hpp): the mosaics, the
// methods' outputs and report.json, staged in the output folder's transaction; and what
// terraweave run and render-tile share with it: a tile's files and facts, the methods' outputs.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/output_folder.hpp"
#include "layers/write.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/stage_clock.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

struct TileFile {
  std::filesystem::path file;  // relative to the output folder, e.g. tiles/height_x0_y1.exr
  std::uintmax_t bytes = 0;
  std::string xxh3_128;
  std::filesystem::path staged;  // where it is in the output folder's staging folder
};

struct RenderedTile {
  TileSpec tile;
  std::vector<TileFile> files;
  double seconds = 0.0;
  std::int64_t forbidden_pixels = 0;        // in its core window
  std::uint64_t xxh64 = 0;                  // of its pixels (detail/tile_stats.hpp)
  std::string input_height, output_height;  // over its core (detail::range_fact)
  // The methods' tile facts, by SynthesisMethod::tile_fact_key.
  std::map<std::string, std::string> method_facts;
  std::optional<CacheStatus> cache;  // with a cache: rendered or reused, and why
};

// Writes <dir>/tiles/<layer>_x<i>_y<j>.{exr,tif} for every layer of one tile's LayerSet.
// Returns the final paths.
std::vector<std::filesystem::path> write_tile_files(LayerSet& layers, const TileSpec& tile,
                                                    const std::filesystem::path& dir,
                                                    OutputStager& stager,
                                                    const WriteOptions& options);

// The mosaics <out>/<layer>.vrt over the tiles' GeoTIFFs and the methods' outputs, as
// terraweave run writes them for a tiled world. Returns the plan's report completed with what the
// tiles found.
RunReport write_job_outputs(const WorldPlan& plan, const std::vector<RenderedTile>& tiles,
                            const std::filesystem::path& out, OutputFolder& transaction);

// The facts of a rendered tile that the run's report and outputs gather (kept with the tile in
// the tile cache and in a worker's tile result): forbidden_pixels, xxh64, input_height,
// output_height, and every method's tile fact under its tile_fact_key.
std::map<std::string, std::string> tile_facts(const WorldPlan& plan, const LayerSet& layers,
                                              const TileSpec& tile);

// Every method's tile fact (SynthesisMethod::tile_fact) under its key, from the tile's height
// layer over `tile.halo_window`.
std::map<std::string, std::string> method_tile_facts(const WorldPlan& plan,
                                                     const Raster<float>& height,
                                                     const TileSpec& tile);

// Per method (plan.methods order), its fact of every tile, in tile order.
using MethodTileFacts = std::vector<std::vector<MethodTileFact>>;

// The methods' facts of one tile (as tile_facts keys them) into `out`; `where` names the tile
// in messages. Throws std::out_of_range when a method's fact is missing.
void add_method_facts(const WorldPlan& plan, const std::map<std::string, std::string>& facts,
                      const std::string& where, MethodTileFacts& out);

// Every method's run outputs (SynthesisMethod::write_outputs), in method order, each timed as
// its outputs stage on `clock` when there is one.
void write_method_outputs(const WorldPlan& plan, MethodTileFacts facts,
                          const std::filesystem::path& out, OutputFolder& transaction,
                          RunReport& report, StageClock* clock);

// <out>/report.json, as terraweave run writes it (by the plan's methods).
void write_job_report(const WorldPlan& plan, const RunReport& report, const PipelineConfig& config,
                      const std::filesystem::path& out, OutputFolder& transaction);

}  // namespace tw::detail
