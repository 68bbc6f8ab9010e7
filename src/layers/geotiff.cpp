// GeoTIFF twins through GDAL: float32, one band per channel, band descriptions = channel
// names and units, tiled + ZSTD (or the options') on all cores, nodata on every band,
// optionally overviews or a COG. QGIS opens them in place.
#include <cpl_string.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "geo/input_guard.hpp"
#include "layers/detail/gdal_init.hpp"
#include "layers/write.hpp"

namespace tw {

namespace {

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

const char* compress_name(TiffCompression compression) {
  switch (compression) {
    case TiffCompression::zstd:
      return "ZSTD";
    case TiffCompression::deflate:
      return "DEFLATE";
    case TiffCompression::lzw:
      return "LZW";
    case TiffCompression::none:
      return "NONE";
  }
  return "ZSTD";
}

// GTiff takes 1, 2, 3; COG the names.
const char* predictor_value(TiffPredictor predictor, bool cog) {
  switch (predictor) {
    case TiffPredictor::none:
      return cog ? "NO" : "1";
    case TiffPredictor::horizontal:
      return cog ? "STANDARD" : "2";
    case TiffPredictor::floating_point:
      return cog ? "FLOATING_POINT" : "3";
  }
  return cog ? "NO" : "1";
}

// The creation options of GTiff or COG (their names differ for the level and predictor).
void set_encoding(CPLStringList& options, const GeoTiffOptions& tiff, bool cog) {
  options.SetNameValue("COMPRESS", compress_name(tiff.compression));
  if (tiff.compression == TiffCompression::zstd)
    options.SetNameValue(cog ? "LEVEL" : "ZSTD_LEVEL", "1");
  if (tiff.compression != TiffCompression::none)
    options.SetNameValue("PREDICTOR", predictor_value(tiff.predictor, cog));
  options.SetNameValue("NUM_THREADS", "ALL_CPUS");
  options.SetNameValue("BIGTIFF", "IF_SAFER");
}

// "m" for heights and distances, "weight" for splat materials, "" for masks.
const char* band_unit(const Layer& layer, const std::string& channel) {
  if (layer.name == "height" || channel == "distance") return "m";
  if (layer.name == "splat") return "weight";
  return "";
}

// Halvings until the smaller side is under 256 pixels (none for small layers).
std::vector<int> overview_levels(const GridSpec& g) {
  std::vector<int> levels;
  for (int f = 2; std::min(g.width, g.height) / (f / 2) > 256; f *= 2) levels.push_back(f);
  return levels;
}

// The plain tiled GeoTIFF; `encoding` is the caller's (a COG's intermediate is uncompressed).
void write_tiled(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
                 const GeoTiffOptions& encoding, bool overviews) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) fail("GDAL has no GTiff driver (writing {})", path.string());
  const GridSpec& g = set.grid;
  CPLStringList options;
  options.SetNameValue("TILED", "YES");
  set_encoding(options, encoding, false);
  options.SetNameValue("INTERLEAVE", "BAND");
  DatasetPtr ds(driver->Create(path.c_str(), g.width, g.height, int(layer.bands.size()),
                               GDT_Float32, options.List()));
  if (!ds)
    fail("cannot create GeoTIFF {} for layer '{}': {}", path.string(), layer.name,
         CPLGetLastErrorMsg());
  auto gt = g.geotransform();
  ds->SetGeoTransform(gt.data());
  if (!set.crs_wkt.empty()) {
    OGRSpatialReference srs;
    if (!import_crs(srs, set.crs_wkt))
      fail("layer set: cannot parse the CRS WKT for {}", path.string());
    ds->SetSpatialRef(&srs);
  }
  for (const auto& [key, value] : encoding.metadata)
    ds->SetMetadataItem(key.c_str(), value.c_str());
  ds->SetMetadataItem("TERRAWEAVE_LAYER", layer.name.c_str());
  // By its channel, not its name: a tile's height layer is named height_x<i>_y<j>.
  const bool is_height = layer.channels == std::vector<std::string>{"height"};
  // The height layer's NaN cells become the source's nodata value when it has one; the other
  // layers declare NaN, which they hold where the height is nodata (blank_where_height_is_nodata,
  // applied where the layers are rendered: the writers write what they are given).
  const bool replace_nan = is_height && set.nodata && !std::isnan(*set.nodata);
  constexpr int kRowsPerChunk = 256;
  std::vector<float> chunk;
  for (std::size_t b = 0; b < layer.bands.size(); ++b) {
    GDALRasterBand* band = ds->GetRasterBand(int(b) + 1);
    band->SetDescription(layer.channels[b].c_str());
    band->SetUnitType(band_unit(layer, layer.channels[b]));
    band->SetNoDataValue(is_height && set.nodata ? *set.nodata : std::nan(""));
    const float* data = layer.bands[b].pixels.data();
    for (int row = 0; row < g.height; row += kRowsPerChunk) {
      const int rows = std::min(kRowsPerChunk, g.height - row);
      const std::size_t offset = std::size_t(row) * g.width, count = std::size_t(rows) * g.width;
      const float* src = data + offset;
      if (replace_nan) {
        chunk.assign(src, src + count);
        const float nodata = float(*set.nodata);
        for (float& v : chunk)
          if (std::isnan(v)) v = nodata;
        src = chunk.data();
      }
      if (band->RasterIO(GF_Write, 0, row, g.width, rows, const_cast<float*>(src), g.width, rows,
                         GDT_Float32, 0, 0) != CE_None)
        fail("cannot write band '{}' of {}: {}", layer.channels[b], path.string(),
             CPLGetLastErrorMsg());
      // Compress and write out this row of tiles now (on NUM_THREADS workers): left in GDAL's
      // block cache, dirty tiles pile up to GDAL_CACHEMAX (5 % of RAM) on top of the layers.
      if (band->FlushCache(false) != CE_None)
        fail("cannot write band '{}' of {}: {}", layer.channels[b], path.string(),
             CPLGetLastErrorMsg());
    }
  }
  if (overviews) {
    const std::vector<int> levels = overview_levels(g);
    if (!levels.empty() &&
        GDALBuildOverviews(GDALDataset::ToHandle(ds.get()), "AVERAGE", int(levels.size()),
                           levels.data(), 0, nullptr, nullptr, nullptr) != CE_None)
      fail("cannot build the overviews of {}: {}", path.string(), CPLGetLastErrorMsg());
  }
  ds.reset();  // flush and close; errors surface here
  if (CPLGetLastErrorType() == CE_Failure)
    fail("cannot finish GeoTIFF {}: {}", path.string(), CPLGetLastErrorMsg());
}

// GDAL's COG driver only copies: an uncompressed tiled GeoTIFF beside the target first.
void write_cog(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               const GeoTiffOptions& options) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("COG");
  if (driver == nullptr) fail("GDAL has no COG driver (writing {})", path.string());
  std::filesystem::path source = path;
  source += ".source.tif";
  GeoTiffOptions raw = options;
  raw.compression = TiffCompression::none;
  write_tiled(set, layer, source, raw, false);
  struct Remove {
    std::filesystem::path p;
    ~Remove() { std::filesystem::remove(p); }
  } remove_source{source};
  DatasetPtr src(GDALDataset::Open(source.c_str(), GDAL_OF_RASTER));
  if (!src) fail("cannot reopen {}: {}", source.string(), CPLGetLastErrorMsg());
  CPLStringList cog;
  set_encoding(cog, options, true);
  cog.SetNameValue("OVERVIEW_RESAMPLING", "AVERAGE");
  DatasetPtr out(driver->CreateCopy(path.c_str(), src.get(), false, cog.List(), nullptr, nullptr));
  if (!out) fail("cannot write COG {}: {}", path.string(), CPLGetLastErrorMsg());
  out.reset();
  if (CPLGetLastErrorType() == CE_Failure)
    fail("cannot finish COG {}: {}", path.string(), CPLGetLastErrorMsg());
}

}  // namespace

void write_geotiff(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
                   const GeoTiffOptions& options) {
  detail::ensure_gdal_registered();
  CPLErrorReset();
  if (options.cog)
    write_cog(set, layer, path, options);
  else
    write_tiled(set, layer, path, options, options.overviews);
}

}  // namespace tw
