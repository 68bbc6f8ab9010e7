#pragma once
// Plan once, render tiles (DESIGN.md, docs/tiles.md). plan_world decides everything that
// belongs to a feature, once for the whole world: features, ribbons, junctions, terrain profiles
// and synthesized placements. render_tile decides everything that belongs to a pixel, for one
// window: heights, splat, avoidance and pattern layers, the same bytes at any tiling.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "geo/heightfield_source.hpp"
#include "layers/layer_set.hpp"
#include "pipeline/config.hpp"
#include "pipeline/method_plan.hpp"
#include "pipeline/run.hpp"
#include "raster/avoidance.hpp"
#include "raster/window_index.hpp"
#include "ribbon/ribbon.hpp"
#include "terrain/height_ops.hpp"

namespace tw {

// One tile of the output grid. `window` is the tile's core; `halo_window` the core plus the
// tiling's overlap on every side, clamped to the grid: what the tile's files hold.
struct TileSpec {
  int index = 0;  // row-major: iy * columns + ix
  int ix = 0;     // column of tiles, west to east (the _x<i> of the file names)
  int iy = 0;     // row of tiles, north to south (the _y<j>)
  Window window;
  Window halo_window;
};

// Tiles of `size` pixels square (the last column and row smaller when size does not divide the
// grid) with `overlap` pixels on every side. size 0: one tile covering the grid (untiled).
// Throws tw::Error on size < 0, overlap < 0, or overlap without tiles.
std::vector<TileSpec> tile_grid(const GridSpec& grid, int size, int overlap);
// The same over `area` of the grid (a region): tiles from its corner, halos clamped to it.
std::vector<TileSpec> tile_grid(const GridSpec& grid, const Window& area, int size, int overlap);

// The grid of a window of `grid`: the same pixels, its origin on the window's north-west corner
// (a tile's layers, a region's report).
GridSpec window_grid(const GridSpec& grid, const Window& window);

// The stem of a tile's files: <layer>_x<ix>_y<iy> (Unreal World Partition / Unity naming).
std::string tile_file_stem(const std::string& layer, const TileSpec& tile);

// A DEM file as a plan names it: what open_heightfield needs to give the plan's grid again, and
// the hash of the file's bytes, so a plan folder is content-addressed without holding them.
struct HeightfieldFile {
  std::string path;            // absolute, as planned: workers must see the same path
  std::string xxh3_128;        // of the file's bytes (filled in by save_plan)
  std::uintmax_t bytes = 0;    // the file's size (idem)
  HeightfieldOptions options;  // resolution, resampling, crs: the plan's grid from the file
};

// Where render_tile reads the heights of its window, before any edit.
struct HeightSource {
  std::string source;  // path or generated:seed=N (messages, reports)
  // A generated world: every window is generated on its own (a window of a generated world
  // equals the same window of the whole one).
  std::optional<GeneratedTerrain> generated;
  // A DEM file: every window is read from it (load_plan reopens it, checking its hash).
  std::optional<HeightfieldFile> file;
  // Otherwise the heights over the plan's grid as ingested, shared by every tile.
  std::shared_ptr<const Raster<float>> heights;
  // The heightfield opened once and read window by window (geo/heightfield_source.hpp; a file
  // or the generated world): read_height_window reads through it.
  std::shared_ptr<const HeightfieldSource> reader;
};

// The heights of `window` of `grid` (the plan's grid). NaN marks nodata.
Raster<float> read_height_window(const HeightSource& source, const GridSpec& grid,
                                 const Window& window);

// The options of render_tile, one per stage (not the pipeline config).
struct RenderOptions {
  // Metres: the avoidance distance layer is min(distance, max_distance), which bounds the halo
  // a tile reads (avoidance.max_distance, docs/tiles.md).
  double avoidance_max_distance = 500.0;
};

struct WorldPlan {
  // The world's grid: every feature, window and index is on it.
  GridSpec grid;
  // The pixels the run writes: the region's (config `region`), else the whole grid. The tiles
  // cut it; its pixels equal the same pixels of a run without the region.
  Window output_window;
  std::string crs_wkt;
  std::optional<double> nodata;
  HeightSource heights;

  // Per class (config order) and feature (reading order): clipped, repaired, conformed lines,
  // and their ribbons (no pieces when shorter than one piece).
  std::vector<std::string> class_names;
  std::vector<std::vector<LineFeature>> lines;
  std::vector<std::vector<Ribbon>> ribbons;
  std::vector<Polygon> junction_discs;  // on the output grid's tolerance
  // The same on the synthesis canvas's tolerance: what syntheses avoid (a plan's syntheses may
  // run later, as tasks: pipeline/synthesis_job.hpp).
  std::vector<Polygon> synthesis_junction_discs;
  // Per class and feature, the synthesis junctions it meets (FeatureRibbons).
  std::vector<std::vector<std::vector<Vec2>>> synthesis_junctions;

  // Existing features (polygons, buffered lines) burnt into the avoidance layer.
  AvoidanceInputs existing;

  // The terrain: features as the terrain module sees them (class order), their parameters and
  // the global plan of profiles (sampled once, so a tile never sees its neighbours' edits).
  std::vector<TerrainFeature> terrain_features;
  TerrainParams terrain_params;
  TerrainPlan terrain;

  // One entry per synthesis method, in the methods' order (pipeline/synthesis_method.hpp):
  // what each planned (its placements, lines, exemplars...), behind the one seam.
  std::vector<MethodPlan> methods;
  // splat_materials() followed by the methods' materials in order of first use: every tile
  // has these channels.
  std::vector<std::string> splat_materials;

  // Which terrain features (terrain_features order) and ribbons (class-major over `ribbons`)
  // can touch a window: their footprint plus reach, binned. Each method's items have their own
  // index (MethodPlan::index).
  WindowIndex feature_index;
  WindowIndex ribbon_index;

  RenderOptions render;
  int tile_size = 0;  // output.tiles.size (0: untiled)
  int tile_overlap = 0;
  std::vector<TileSpec> tiles;

  // What the plan found: grid, classes and features (with their syntheses and earthwork),
  // stage timings; run_pipeline completes it.
  RunReport report;
};

struct PlanOptions {
  std::optional<std::string> backend;  // replaces every class's backend
  bool synthesize = true;              // false: no synthesis (validate)
  // Reuses and stores syntheses there (`--cache`, docs/cache.md); absent: the config's `cache`,
  // or none.
  std::optional<std::filesystem::path> cache_dir;
  // The synthesis methods, in plan order; empty: the built-in ones
  // (builtin_synthesis_methods, pipeline/synthesis_method.hpp).
  std::vector<const SynthesisMethod*> methods;
};

// Ingest, conformance, ribbons, junctions, the terrain plan and the syntheses. Throws tw::Error
// naming the file, key, FID or piece of the first bad input; warnings go to `warnings`.
WorldPlan plan_world(const PipelineConfig& config, const PlanOptions& options, Warnings& warnings);

// The plan's methods, in its order (those that made it: a run's report.json is written by them).
std::vector<const SynthesisMethod*> methods_in(const WorldPlan& plan);

// Builds feature_index, ribbon_index and every method entry's index from the plan's features,
// ribbons and the methods' items (plan_world does; a plan read back from files calls it again).
void index_plan(WorldPlan& plan);

// Pixels beyond a window that its avoidance layer reads: the distance cap, plus a pixel.
int avoidance_halo_pixels(const WorldPlan& plan);

// The layers of `tile.halo_window`: "height", "splat", "avoidance" on a grid whose origin is
// the window's corner; every pixel equals the same pixel of an untiled render. Reads the
// heights of the window only, and only the features whose footprint (+ reach) meets it.
LayerSet render_tile(const WorldPlan& plan, const TileSpec& tile);

}  // namespace tw
