// GeoTIFF twins through GDAL: float32, one band per channel, band descriptions = channel
// names, tiled + ZSTD on all cores, nodata on the height layer. QGIS opens them in place.
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

}  // namespace

void write_geotiff(const LayerSet& set, const Layer& layer, const std::filesystem::path& path) {
  detail::ensure_gdal_registered();
  CPLErrorReset();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) fail("GDAL has no GTiff driver (writing {})", path.string());
  const GridSpec& g = set.grid;
  CPLStringList options;
  options.SetNameValue("TILED", "YES");
  options.SetNameValue("COMPRESS", "ZSTD");
  options.SetNameValue("ZSTD_LEVEL", "1");
  options.SetNameValue("NUM_THREADS", "ALL_CPUS");
  options.SetNameValue("BIGTIFF", "IF_SAFER");
  options.SetNameValue("INTERLEAVE", "BAND");
  std::unique_ptr<GDALDataset, DatasetCloser> ds(driver->Create(
      path.c_str(), g.width, g.height, int(layer.bands.size()), GDT_Float32, options.List()));
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
  // By its channel, not its name: a tile's height layer is named height_x<i>_y<j>.
  const bool is_height = layer.channels == std::vector<std::string>{"height"};
  // The height layer's NaN cells become the source's nodata value when it has one.
  const bool replace_nan = is_height && set.nodata && !std::isnan(*set.nodata);
  constexpr int kRowsPerChunk = 256;
  std::vector<float> chunk;
  for (std::size_t b = 0; b < layer.bands.size(); ++b) {
    GDALRasterBand* band = ds->GetRasterBand(int(b) + 1);
    band->SetDescription(layer.channels[b].c_str());
    if (is_height) band->SetNoDataValue(set.nodata ? *set.nodata : std::nan(""));
    const float* data = layer.bands[b].pixels.data();
    for (int row = 0; row < g.height; row += kRowsPerChunk) {
      const int rows = std::min(kRowsPerChunk, g.height - row);
      const float* src = data + std::size_t(row) * g.width;
      if (replace_nan) {
        chunk.assign(src, src + std::size_t(rows) * g.width);
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
  ds.reset();  // flush and close; errors surface here
  if (CPLGetLastErrorType() == CE_Failure)
    fail("cannot finish GeoTIFF {}: {}", path.string(), CPLGetLastErrorMsg());
}

}  // namespace tw
