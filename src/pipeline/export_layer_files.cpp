#include "pipeline/export_layer_files.hpp"

#include <cmath>

#include "core/error.hpp"
#include "geo/heightfield.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

// The heights of `path` over `grid`: the raster itself when it is on the grid, else the DEM read
// with the run's cell size and CRS (read_heightfield's rules, as the pipeline read it), the
// grid a window of it. Throws naming the file when neither holds.
Raster<float> input_heights_on(const fs::path& path, const LayerSet& run, Resampling resampling) {
  const GridSpec& grid = run.grid;
  {
    LayerSet probe;
    const Layer as_is = read_geotiff_layer(path, "height", probe);
    if (probe.grid == grid) return as_is.bands.front();
  }
  HeightfieldOptions options;
  options.resolution = grid.pixel_width;
  options.crs = run.crs_wkt;
  options.resampling = resampling;
  const Heightfield dem = read_heightfield(path.string(), options);
  const double col = (grid.origin_x - dem.grid.origin_x) / dem.grid.pixel_width;
  const double row = (dem.grid.origin_y - grid.origin_y) / dem.grid.pixel_height;
  const int c0 = int(std::lround(col)), r0 = int(std::lround(row));
  if (std::abs(dem.grid.pixel_width - grid.pixel_width) > 1e-9 * grid.pixel_width ||
      std::abs(col - c0) > 1e-6 || std::abs(row - r0) > 1e-6 || c0 < 0 || r0 < 0 ||
      c0 + grid.width > dem.grid.width || r0 + grid.height > dem.grid.height)
    fail(
        "--input-height {}: the run's grid ({} x {} cells of {} m) is not a window of it; give "
        "the DEM the pipeline read or a raster on the run's grid",
        path.string(), grid.width, grid.height, grid.pixel_width);
  Raster<float> out(grid.width, grid.height);
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) out.at(c, r) = dem.height.at(c0 + c, r0 + r);
  return out;
}

}  // namespace

EngineExportResult export_layer_files(const ExportFiles& files,
                                      const std::vector<ExportCurve>& curves,
                                      EngineExportOptions options, int run_tile_size,
                                      const fs::path& dir, OutputStager& stager,
                                      const std::optional<fs::path>& input_height,
                                      Resampling input_resampling) {
  options.tile_size = export_tile_size(options, run_tile_size);
  if (*options.tile_size > 0) return export_tiles_for_engine(files, curves, options, dir, stager);
  LayerSet set;
  set.layers.push_back(read_geotiff_layer(files.height, "height", set));
  if (files.splat) set.layers.push_back(read_geotiff_layer(*files.splat, "splat", set));
  if (!files.crs_wkt.empty()) set.crs_wkt = files.crs_wkt;
  std::optional<Raster<float>> input;
  if (input_height) input = input_heights_on(*input_height, set, input_resampling);
  return export_for_engine(set, curves, options, dir, stager, input ? &*input : nullptr);
}

}  // namespace tw
