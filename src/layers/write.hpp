#pragma once
// Writers of a LayerSet: EXR (codec and pixel type per layer, named channels, georeferencing),
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

// How EXR pixels are compressed (OpenEXR's codecs). Lossless: rle, zips (zlib, one row per
// chunk), zip (zlib, 16 rows), piz (wavelet + Huffman). Lossy on float32: pxr24 (24-bit
// floats), b44 and dwaa/dwab (half-float codecs: 32-bit channels go in raw / are quantized).
// `automatic` picks per layer from the measurements of docs/performance.md
// (exr_compression_for): zip for layers of runs (splat weights, masks, capped distances): at
// zlib level 1 it costs about what rle does and packs them 3-6x smaller; none for noisy floats
// (heights), where every lossless codec saves under a tenth for 10-20x a raw write.
enum class ExrCompression { automatic, none, rle, zips, zip, piz, pxr24, b44, dwaa, dwab };
// "automatic", "none", "rle", "zips", "zip", ... (the enumerator's name).
const char* to_string(ExrCompression compression);

// The EXR channels' pixel type. `automatic`: half floats for splat weights (in [0, 1]: steps
// of 2^-11 at most, 0 and 1 exact), float32 for every other layer (heights and distances need
// more than half's 3 significant digits).
enum class ExrPixels { automatic, float32, half };
// True when `pixels` stores this layer as half floats.
bool exr_half_for(const Layer& layer, ExrPixels pixels);

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
  int exr_zip_level = 1;  // zlib level when exr_compression is zip or zips (1-9)
  ExrPixels exr_pixels = ExrPixels::automatic;
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
// automatic resolves through exr_compression_for(layer), pixels through exr_half_for. Half
// floats keep 3 significant digits (0.25 m steps at 500 m; NaN stays NaN).
void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               ExrCompression compression, int zip_level = 1,
               ExrPixels pixels = ExrPixels::float32);
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

// What `automatic` picks for this layer: zip when at least a quarter of sampled pixels (every
// 64th row) repeat their left neighbour bit for bit, else none.
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
