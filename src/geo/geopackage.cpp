#include "geo/geopackage.hpp"

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "core/error.hpp"
#include "geo/detail/gdal_support.hpp"

namespace tw {

void GeoPackageWriter::DatasetCloser::operator()(GDALDataset* dataset) const {
  GDALClose(GDALDataset::ToHandle(dataset));
}

GeoPackageWriter::GeoPackageWriter(std::filesystem::path path, const std::string& crs)
    : path_(std::move(path)) {
  detail::ensure_gdal_registered();
  // The writing thread's setting: GDAL reads it when it fills gpkg_contents.last_change.
  CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z");
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!driver) fail("{}: GDAL has no GPKG driver", path_.string());
  if (!crs.empty()) {
    srs_ = std::make_unique<OGRSpatialReference>();
    if (!detail::import_traditional_srs(*srs_, crs)) fail("{}: unreadable CRS", path_.string());
  }
  dataset_.reset(driver->Create(path_.string().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!dataset_) fail("{}: cannot create the GeoPackage", path_.string());
}

GeoPackageWriter::~GeoPackageWriter() = default;
GeoPackageWriter::GeoPackageWriter(GeoPackageWriter&&) noexcept = default;
GeoPackageWriter& GeoPackageWriter::operator=(GeoPackageWriter&&) noexcept = default;

OGRLayer& GeoPackageWriter::create_layer(const std::string& name, OGRwkbGeometryType type) {
  OGRLayer* layer = dataset_->CreateLayer(name.c_str(), srs_.get(), type, nullptr);
  if (!layer) fail("{}: cannot create layer '{}'", path_.string(), name);
  return *layer;
}

void GeoPackageWriter::add_fields(
    OGRLayer& layer, std::initializer_list<std::pair<const char*, OGRFieldType>> fields) {
  for (auto [name, type] : fields) {
    OGRFieldDefn field(name, type);
    if (layer.CreateField(&field) != OGRERR_NONE)
      fail("{}: cannot add field {} to layer '{}'", path_.string(), name, layer.GetName());
  }
}

void GeoPackageWriter::set_metadata(OGRLayer& layer,
                                    const std::vector<std::pair<std::string, std::string>>& items) {
  for (const auto& [name, value] : items)
    if (layer.SetMetadataItem(name.c_str(), value.c_str()) != CE_None)
      fail("{}: cannot set metadata {} on layer '{}'", path_.string(), name, layer.GetName());
}

GeoPackageWriter create_geopackage(const std::filesystem::path& path, const std::string& crs) {
  return GeoPackageWriter(path, crs);
}

}  // namespace tw
