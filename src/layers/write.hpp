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

// EXR header attributes carrying the georeferencing: ours, and GDAL's EXR driver's own keys
// (gdal:geoTransform is an M33d: row 0 = gt[1] gt[2] gt[0], row 1 = gt[4] gt[5] gt[3]).
inline constexpr const char* kExrGdalCrsAttribute = "gdal:crsWkt";                 // string
inline constexpr const char* kExrGdalGeotransformAttribute = "gdal:geoTransform";  // M33d
inline constexpr const char* kExrCrsAttribute = "terraweave:crs_wkt";              // string
inline constexpr const char* kExrGeotransformAttribute =
    "terraweave:geotransform";                                                  // string, 6 x %.17g
inline constexpr const char* kExrOriginAttribute = "terraweave:origin";         // V2d (x, y)
inline constexpr const char* kExrPixelSizeAttribute = "terraweave:pixel_size";  // V2d (w, h)
// The layer's name and its channel names in band order (the GeoTIFF's), so that a reader maps
// the EXR channels (exr_channel_names) back to materials.
inline constexpr const char* kExrLayerAttribute = "terraweave:layer";        // string
inline constexpr const char* kExrChannelsAttribute = "terraweave:channels";  // string vector

// How EXR pixels are compressed. Heights and distances are noisy floats: ZIP (zlib) saves only
// about a fifth of their bytes at ~20x the cost of RLE, and RLE saves nothing on them; splat
// weights and masks are runs, which RLE packs to a few percent. `automatic` picks per layer:
// rle when at least a quarter of sampled pixels repeat their left neighbour, else none.
// docs/performance.md has the measurements.
enum class ExrCompression { automatic, none, rle, zip };

// GeoTIFF encoding (docs/layers.md). The predictor helps deflate/lzw/zstd on smooth data:
// floating_point (GDAL PREDICTOR=3) on heights, horizontal (2) on integer-like bands.
enum class TiffCompression { zstd, deflate, lzw, none };
enum class TiffPredictor { none, horizontal, floating_point };

struct GeoTiffOptions {
  TiffCompression compression = TiffCompression::zstd;
  TiffPredictor predictor = TiffPredictor::none;
  // A Cloud-Optimized GeoTIFF through GDAL's COG driver (tiled, overviews inside, ordered for
  // HTTP range reads) instead of a plain tiled GeoTIFF.
  bool cog = false;
  // Internal overviews (AVERAGE, halving until under 256 pixels) on a plain GeoTIFF.
  bool overviews = false;
  // Dataset metadata (provenance: TERRAWEAVE_VERSION, PIPELINE, ...), written on every file.
  std::vector<std::pair<std::string, std::string>> metadata;
};

struct WriteOptions {
  bool exr = true;
  bool geotiff = true;
  bool preview = true;
  ExrCompression exr_compression = ExrCompression::automatic;
  int exr_zip_level = 1;  // zlib level when exr_compression is zip (1-9)
  bool exr_half = false;  // 16-bit half floats instead of 32-bit
  GeoTiffOptions geotiff_options;
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
// automatic resolves through exr_compression_for(layer). half: pixels stored as 16-bit half
// floats (3 significant digits: 0.25 m steps at 500 m; NaN stays NaN).
void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               ExrCompression compression, int zip_level = 1, bool half = false);
// The EXR channel of each band, following OpenEXR's layer conventions so that RGBA readers
// (Imf::RgbaInputFile, Nuke, Houdini, Unreal) find them: a one-band layer is "Y" (luminance);
// the splat layer's materials go four by four into layers splat0, splat1, ... as R, G, B, A
// (material i -> splat<i/4>.<RGBA[i%4]>, in band order); other bands are "<channel>.Y".
std::vector<std::string> exr_channel_names(const Layer& layer);
// Every band carries a nodata value: the height layer the source's (NaN when it has none),
// the others NaN, written on the cells where the height is nodata. Bands are described by
// their channel names and carry units (metre for height and distance, weight for splat).
void write_geotiff(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
                   const GeoTiffOptions& options = {});
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
  std::vector<std::string> channels;  // in band order, the layer's names (height, splat.road, ...)
  std::vector<std::string> exr_channels;  // the EXR channel of each band (Y, splat0.R, ...)
  std::vector<Raster<float>> bands;
  std::string crs_wkt;
  std::string geotransform;  // the string attribute
  Vec2 origin;
  Vec2 pixel_size;
};
ExrContents read_exr(const std::filesystem::path& path);

}  // namespace tw
