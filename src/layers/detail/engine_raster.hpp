#pragma once
// What every engine export does to the layers: fill nodata, resample onto the heightmap's
// vertices, quantize to 16 bits (heights) or 8 bits summing to 255 (weights), write PNG / RAW.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/grid.hpp"

namespace tw::detail {

// `height` with every NaN replaced: by `value`, or by GDALFillNodata from the nearest valid
// cells (search distance: the whole grid, no smoothing). Fails when no cell is valid.
Raster<float> fill_nodata(const Raster<float>& height, std::optional<double> value);

// An nx x ny grid whose cell centres are the heightmap's vertices: the first and last ones on
// the outer cell centres of `grid`, so the terrain spans (width - 1) cells.
GridSpec vertex_grid(const GridSpec& grid, int nx, int ny);
// An nx x ny grid of texels covering the same span as vertex_grid (alphamaps, Unity).
GridSpec texel_grid(const GridSpec& grid, int nx, int ny);

// Bilinear (an area mean when coarser; geo/resample.hpp) of a nodata-free band onto `to`.
Raster<float> resample_band(const Raster<float>& band, const GridSpec& from, const GridSpec& to);

struct Heightmap16 {
  int width = 0, height = 0;
  std::vector<std::uint16_t> pixels;  // row 0 = north
  double min = 0.0, max = 0.0;        // metres at 0 and 65535
  double step() const { return (max - min) / 65535.0; }
};
// min -> 0, max -> 65535, rounded to nearest (a flat world: all 0, max = min).
Heightmap16 quantize_heights(const Raster<float>& heights);
// The same with min and max given (a tile of a larger heightmap: one scale for all tiles).
Heightmap16 quantize_heights(const Raster<float>& heights, double min, double max);

// One 8-bit map per material, summing to exactly 255 per pixel: floor(255 w) plus the
// remainder to the largest fractions (lowest index on ties). NaN weights count as 0; a pixel
// without weight goes to material 0.
std::vector<std::vector<std::uint8_t>> quantize_weights(const std::vector<Raster<float>>& weights);

// PNG through GDAL: `bands` of width x height, 8-bit (Byte) or 16-bit (UInt16) gray / RGBA.
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<const std::uint8_t*>& bands);
void write_png16(const std::filesystem::path& path, const Heightmap16& map);
// 16-bit little-endian samples; bottom_up: row 0 of the file is the south edge.
void write_raw16(const std::filesystem::path& path, const Heightmap16& map, bool bottom_up);

}  // namespace tw::detail
