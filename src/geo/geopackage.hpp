#pragma once
// A new GeoPackage to write features into: GDAL's GPKG driver, layers in one CRS, and the same
// bytes for the same features (gpkg_contents.last_change holds the time of writing unless
// OGR_CURRENT_DATE fixes it; manifest hashes and the determinism tests compare the bytes).
#include <ogr_core.h>

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class GDALDataset;
class OGRLayer;
class OGRSpatialReference;

namespace tw {

class GeoPackageWriter {
 public:
  ~GeoPackageWriter();  // closes the file (what GDAL deferred is written then)
  GeoPackageWriter(GeoPackageWriter&&) noexcept;
  GeoPackageWriter& operator=(GeoPackageWriter&&) noexcept;

  GDALDataset& dataset() { return *dataset_; }
  // A layer of `type` in the package's CRS (none when it was created without one).
  OGRLayer& create_layer(const std::string& name, OGRwkbGeometryType type);
  // Adds the fields to a layer of this package, in order.
  void add_fields(OGRLayer& layer,
                  std::initializer_list<std::pair<const char*, OGRFieldType>> fields);
  // Name=value items on a layer of this package (GDAL keeps them in gpkg_metadata, referenced
  // from gpkg_metadata_reference with scope 'table'): what made its features, for whoever opens
  // the file later (ogrinfo, QGIS, a pipeline).
  void set_metadata(OGRLayer& layer, const std::vector<std::pair<std::string, std::string>>& items);

 private:
  friend GeoPackageWriter create_geopackage(const std::filesystem::path&, const std::string&);
  GeoPackageWriter(std::filesystem::path path, const std::string& crs);
  struct DatasetCloser {
    void operator()(GDALDataset* dataset) const;
  };
  std::filesystem::path path_;
  std::unique_ptr<OGRSpatialReference> srs_;  // null: no CRS
  std::unique_ptr<GDALDataset, DatasetCloser> dataset_;
};

// Creates `path` (not there yet) as a GeoPackage whose layers are in `crs` (WKT, "EPSG:n", a PROJ
// string; "" for none). Throws tw::Error naming the path when GDAL has no GPKG driver, the file
// cannot be created, a layer or field cannot be added, or `crs` is not a CRS.
GeoPackageWriter create_geopackage(const std::filesystem::path& path, const std::string& crs);

}  // namespace tw
