// A layer's GeoTIFF twin (or its EXR, through LayerRaster) read back (terraweave export reads
// finished runs this way).
#include <gdal_priv.h>

#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "layers/detail/gdal_cache.hpp"
#include "layers/detail/gdal_init.hpp"
#include "layers/export.hpp"
#include "layers/layer_raster.hpp"

namespace tw {

Layer read_geotiff_layer(const std::filesystem::path& path, const std::string& name,
                         LayerSet& set) {
  detail::ensure_gdal_registered();
  // The layer is read whole into memory once: blocks cached on top of it would double it.
  const detail::ScopedGdalCacheMax cache(detail::kExportGdalCacheBytes);
  const LayerRaster raster(path);
  GDALDataset* ds = &raster.dataset();
  std::array<double, 6> gt{};
  if (ds->GetGeoTransform(gt.data()) != CE_None || gt[2] != 0.0 || gt[4] != 0.0 || gt[5] >= 0.0)
    fail("{}: not a north-up georeferenced raster", path.string());
  const GridSpec grid{ds->GetRasterXSize(), ds->GetRasterYSize(), gt[0], gt[3], gt[1], -gt[5]};
  if (set.grid.width == 0) {
    set.grid = grid;
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
      char* wkt = nullptr;
      srs->exportToWkt(&wkt);
      set.crs_wkt = wkt ? wkt : "";
      CPLFree(wkt);
    }
  } else if (!(set.grid == grid)) {
    fail("{}: its grid differs from the other layers'", path.string());
  }
  Layer layer;
  layer.name = name;
  for (int b = 1; b <= ds->GetRasterCount(); ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b);
    const char* description = band->GetDescription();
    layer.channels.push_back(description && *description ? description : fmt::format("band{}", b));
    Raster<float>& r = layer.bands.emplace_back(grid.width, grid.height);
    if (band->RasterIO(GF_Read, 0, 0, grid.width, grid.height, r.pixels.data(), grid.width,
                       grid.height, GDT_Float32, 0, 0) != CE_None)
      fail("cannot read band {} of {}: {}", b, path.string(), CPLGetLastErrorMsg());
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    if (has_nodata && !std::isnan(nodata)) {
      for (float& v : r.pixels)
        if (v == float(nodata)) v = std::nanf("");
    }
  }
  return layer;
}

}  // namespace tw
