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

// Square pixels: an engine heightmap of width x height vertices `spacing` metres apart on X and
// Y alike, the world's vertices a window of it starting at the engine's origin corner (the
// world's corner cell centre there), the rest padding. The world holds the vertices that lie
// within its outer cell centres: on an axis whose span is not a whole number of spacings, the
// strip beyond the last vertex (narrower than one spacing) is cropped, never stretched.
enum class OriginCorner { north_west, south_west };
struct EngineVertices {
  int width = 0, height = 0;  // heightmap samples
  double spacing = 0.0;       // metres between neighbouring vertices, X and Y
  GridSpec data;              // the world's vertices (cell centres of this grid)
  Window world;               // where `data` lies in the heightmap (row 0 north)
  bool padded() const { return world.width < width || world.height < height; }
};
// The spacing that fits the world's spans into nx by ny vertices on both axes: the larger of the
// two axes' (cells - 1) x cell / (n - 1) (exactly the cell size when n is the cell count).
double fitting_spacing(const GridSpec& world, int nx, int ny);
// Vertices `spacing` apart over `span` metres, the first at 0: floor(span / spacing) + 1.
int vertices_over(double span, double spacing);
EngineVertices engine_vertices(const GridSpec& world, int width, int height, double spacing,
                               OriginCorner corner);
// Texels (Unity's control maps) `spacing` wide from the corner's cell centre: as many as have
// their centre within the world, `width` x `height` in all.
EngineVertices engine_texels(const GridSpec& world, int width, int height, double spacing,
                             OriginCorner corner);
// `data` (the world's vertices) placed at v.world in a v.width x v.height raster; every padding
// sample repeats the nearest world sample on its row, then on its column (the edge carried on:
// no cliff at the world's border). `fill` instead when given.
Raster<float> pad_to_engine(const Raster<float>& data, const EngineVertices& v,
                            std::optional<float> fill = std::nullopt);
// 255 on the world's samples, 0 on padding.
std::vector<std::uint8_t> world_mask(const EngineVertices& v);

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
// A 32-bit float EXR, one channel R, ZIP-compressed (what Godot's EXR loader reads as
// FORMAT_RF), row 0 north; written through OpenEXR for the same bytes on every run.
void write_float_exr(const std::filesystem::path& path, int width, int height, const float* pixels);
// 16-bit little-endian samples; bottom_up: row 0 of the file is the south edge.
void write_raw16(const std::filesystem::path& path, const Heightmap16& map, bool bottom_up);

}  // namespace tw::detail
