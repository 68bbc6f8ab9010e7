#include "layers/layer_raster.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cstdint>

#include "core/error.hpp"
#include "geo/input_guard.hpp"
#include "layers/detail/gdal_init.hpp"
#include "layers/write.hpp"

namespace tw {

namespace {

// A MEM dataset over the EXR's bands (no copy: DATAPOINTER), georeferenced from its attributes.
GDALDataset* memory_dataset(const std::filesystem::path& path, ExrContents& exr) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("MEM");
  if (driver == nullptr) fail("GDAL has no MEM driver (reading {})", path.string());
  GDALDataset* ds = driver->Create("", exr.width, exr.height, 0, GDT_Float32, nullptr);
  if (ds == nullptr) fail("cannot hold {} in memory: {}", path.string(), CPLGetLastErrorMsg());
  for (std::size_t b = 0; b < exr.bands.size(); ++b) {
    CPLStringList options;
    options.SetNameValue(
        "DATAPOINTER",
        CPLSPrintf("%llu", static_cast<unsigned long long>(
                               reinterpret_cast<std::uintptr_t>(exr.bands[b].pixels.data()))));
    if (ds->AddBand(GDT_Float32, options.List()) != CE_None) {
      GDALClose(ds);
      fail("cannot hold {} in memory: {}", path.string(), CPLGetLastErrorMsg());
    }
    ds->GetRasterBand(int(b) + 1)->SetDescription(exr.channels[b].c_str());
  }
  double gt[6] = {exr.origin.x, exr.pixel_size.x, 0.0, exr.origin.y, 0.0, -exr.pixel_size.y};
  ds->SetGeoTransform(gt);
  if (!exr.crs_wkt.empty()) {
    OGRSpatialReference srs;
    if (import_crs(srs, exr.crs_wkt)) ds->SetSpatialRef(&srs);
  }
  return ds;
}

}  // namespace

LayerRaster::LayerRaster(const std::filesystem::path& path) {
  detail::ensure_gdal_registered();
  CPLErrorReset();
  if (path.extension() == ".exr") {
    exr_ = std::make_unique<ExrContents>(read_exr(path));
    if (exr_->pixel_size.x <= 0 || exr_->pixel_size.y <= 0)
      fail("{}: no terraweave georeferencing (terraweave:pixel_size)", path.string());
    dataset_ = memory_dataset(path, *exr_);
    return;
  }
  dataset_ = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  if (dataset_ == nullptr) fail("cannot open {}: {}", path.string(), CPLGetLastErrorMsg());
}

LayerRaster::~LayerRaster() {
  if (dataset_ != nullptr) GDALClose(dataset_);
}

}  // namespace tw
