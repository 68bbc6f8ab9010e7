#pragma once
// What `terraweave finish` writes besides the tiles (pipeline/job.hpp): the mosaics, the
// placements, the preview and report.json, staged in the output folder's transaction.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/output_folder.hpp"
#include "layers/write.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/instance_heights.hpp"
#include "pipeline/plan.hpp"

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
  std::string instance_heights;             // detail::instance_heights_fact
  std::optional<CacheStatus> cache;         // with a cache: rendered or reused, and why
};

// Writes <dir>/tiles/<layer>_x<i>_y<j>.{exr,tif} for every layer of one tile's LayerSet.
// Returns the final paths.
std::vector<std::filesystem::path> write_tile_files(LayerSet& layers, const TileSpec& tile,
                                                    const std::filesystem::path& dir,
                                                    OutputStager& stager,
                                                    const WriteOptions& options);

// The mosaics <out>/<layer>.vrt over the tiles' GeoTIFFs and placements/, as terraweave run
// writes them for a tiled world. Returns the plan's report completed with what the tiles found.
RunReport write_job_outputs(const WorldPlan& plan, const PipelineConfig& config,
                            const std::vector<RenderedTile>& tiles,
                            const std::filesystem::path& out, OutputFolder& transaction);

// placements/<class>_<fid>.json for every synthesized feature (a multi-part FID adds _<part>),
// named in the report.
void write_placements(const WorldPlan& plan, const std::filesystem::path& out,
                      OutputFolder& transaction, RunReport& report);

// areas.gpkg (layers strokes and instances), instances.csv and instances.json of the plan's
// `kind: area` classes (docs/shape-patterns.md), the instances' z from `heights`; nothing when
// it has none.
void write_area_outputs(const WorldPlan& plan, const InstanceHeights& heights,
                        const std::filesystem::path& out, OutputFolder& transaction);

// ornaments.gpkg of the plan's grown classes (one layer per class, named by it; FIDs as the
// class's features'); nothing when it has none.
void write_ornament_outputs(const WorldPlan& plan, const std::filesystem::path& out,
                            OutputFolder& transaction);

// <out>/report.json, as terraweave run writes it.
void write_job_report(const RunReport& report, const PipelineConfig& config,
                      const std::filesystem::path& out, OutputFolder& transaction);

}  // namespace tw::detail
