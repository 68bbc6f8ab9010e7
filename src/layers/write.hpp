#pragma once
// Writers of a LayerSet: EXR (float32, ZIP, named channels, georeferencing attributes),
// GeoTIFF twins through GDAL, and a PNG preview. Every file is staged (an OutputTransaction
// or an OutputFolder), so a failed run leaves previous outputs untouched.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/atomic_output.hpp"
#include "layers/layer_set.hpp"

namespace tw {

// EXR header attributes carrying the georeferencing.
inline constexpr const char* kExrCrsAttribute = "terraweave:crs_wkt";  // string
inline constexpr const char* kExrGeotransformAttribute =
    "terraweave:geotransform";                                                  // string, 6 x %.17g
inline constexpr const char* kExrOriginAttribute = "terraweave:origin";         // V2d (x, y)
inline constexpr const char* kExrPixelSizeAttribute = "terraweave:pixel_size";  // V2d (w, h)

// How EXR pixels are compressed. Heights and distances are noisy floats: ZIP (zlib) saves only
// about a fifth of their bytes at ~20x the cost of RLE, and RLE saves nothing on them; splat
// weights and masks are runs, which RLE packs to a few percent. `automatic` picks per layer:
// rle when at least a quarter of sampled pixels repeat their left neighbour, else none.
// docs/performance.md has the measurements.
enum class ExrCompression { automatic, none, rle, zip };

struct WriteOptions {
  bool exr = true;
  bool geotiff = true;
  bool preview = true;
  ExrCompression exr_compression = ExrCompression::automatic;
  int exr_zip_level = 1;                         // zlib level when exr_compression is zip (1-9)
  int preview_max_size = 2048;                   // longest side of preview.png in pixels
  std::vector<std::vector<Vec2>> preview_lines;  // world metres, drawn on the preview
};

// Writes <dir>/<layer>.exr (+ <layer>.tif) for each layer and <dir>/preview.png, staged in
// `tx` (the caller commits). Returns the final paths.
std::vector<std::filesystem::path> write_layer_set(const LayerSet& set,
                                                   const std::filesystem::path& dir,
                                                   OutputStager& tx,
                                                   const WriteOptions& options = {});

// Single-file writers (they write `path` directly; stage it first for atomicity).
// zip_level: zlib level 1 (fastest; float heights barely compress better at higher levels) - 9.
void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               int zip_level = 1);
// The same with any compression; all use every core (OpenEXR's global thread pool).
// automatic resolves through exr_compression_for(layer).
void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               ExrCompression compression, int zip_level = 1);
void write_geotiff(const LayerSet& set, const Layer& layer, const std::filesystem::path& path);
// Hillshade of "height" tinted by every "splat" material (weighted mean of their colours,
// splat.base in an elevation tint) with `lines` (world metres) drawn on top; 8-bit RGB.
void write_preview_png(const LayerSet& set, const std::filesystem::path& path,
                       const std::vector<std::vector<Vec2>>& lines = {}, int max_size = 2048);

// The preview colour (8-bit RGB) of a splat channel: fixed ones for the terrain's materials and
// the demo's patterns, any other a distinct hue derived from its name (deterministic).
using Rgb8 = std::array<std::uint8_t, 3>;
Rgb8 preview_material_colour(const std::string& channel);

// What `automatic` picks for this layer: rle or none (never automatic).
ExrCompression exr_compression_for(const Layer& layer);

// What an EXR holds, read back (for tests and tools).
struct ExrContents {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // in file order (alphabetical, as EXR stores them)
  std::vector<Raster<float>> bands;
  std::string crs_wkt;
  std::string geotransform;  // the string attribute
  Vec2 origin;
  Vec2 pixel_size;
};
ExrContents read_exr(const std::filesystem::path& path);

}  // namespace tw
