#include "geo_test_data.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <GeographicLib/UTMUPS.hpp>

#include <memory>
#include <stdexcept>

#include "core/error.hpp"

namespace tw::test {
namespace {

struct Closer {
  void operator()(GDALDataset* dataset) const { GDALClose(GDALDataset::ToHandle(dataset)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, Closer>;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::runtime_error("test data: " + what);
}

}  // namespace

void write_geotiff(const std::string& path, const DemSpec& spec) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  DatasetPtr dataset(
      driver->Create(path.c_str(), spec.width, spec.height, spec.bands, GDT_Float32, nullptr));
  require(dataset != nullptr, "create " + path);
  std::array<double, 6> gt = spec.geotransform;
  dataset->SetGeoTransform(gt.data());
  if (!spec.crs.empty()) {
    OGRSpatialReference srs;
    require(srs.SetFromUserInput(spec.crs.c_str()) == OGRERR_NONE, "crs " + spec.crs);
    dataset->SetSpatialRef(&srs);
  }
  for (int b = 1; b <= spec.bands; ++b) {
    GDALRasterBand* band = dataset->GetRasterBand(b);
    if (spec.nodata) band->SetNoDataValue(*spec.nodata);
    if (!spec.unit.empty()) band->SetUnitType(spec.unit.c_str());
    std::vector<float> pixels(std::size_t(spec.width) * spec.height);
    for (int row = 0; row < spec.height; ++row) {
      for (int col = 0; col < spec.width; ++col) {
        pixels[std::size_t(row) * spec.width + col] =
            float(spec.value(col, row) + 1000.0 * (b - 1));
      }
    }
    require(band->RasterIO(GF_Write, 0, 0, spec.width, spec.height, pixels.data(), spec.width,
                           spec.height, GDT_Float32, 0, 0) == CE_None,
            "write " + path);
  }
}

void write_vector(const std::string& path, const std::string& driver_name,
                  const std::string& layer_name, const std::string& crs,
                  const std::vector<TestFeature>& features) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name.c_str());
  require(driver != nullptr, "driver " + driver_name);
  DatasetPtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  require(dataset != nullptr, "create " + path);
  std::unique_ptr<OGRSpatialReference> srs;
  if (!crs.empty()) {
    srs = std::make_unique<OGRSpatialReference>();
    require(srs->SetFromUserInput(crs.c_str()) == OGRERR_NONE, "crs " + crs);
  }
  OGRLayer* layer = dataset->CreateLayer(layer_name.c_str(), srs.get(), wkbUnknown, nullptr);
  require(layer != nullptr, "layer " + layer_name);
  OGRFieldDefn kind("kind", OFTString);
  OGRFieldDefn width("width", OFTReal);
  layer->CreateField(&kind);
  layer->CreateField(&width);
  for (const TestFeature& spec : features) {
    OGRFeature feature(layer->GetLayerDefn());
    if (spec.fid != 0) feature.SetFID(spec.fid);
    feature.SetField("kind", spec.kind.c_str());
    if (spec.width) feature.SetField("width", *spec.width);
    if (!spec.raw_points.empty()) {
      OGRLineString line;
      for (std::size_t i = 0; i + 1 < spec.raw_points.size(); i += 2) {
        line.addPoint(spec.raw_points[i], spec.raw_points[i + 1]);
      }
      feature.SetGeometry(&line);
    } else if (!spec.wkt.empty()) {
      OGRGeometry* geometry = nullptr;
      require(
          OGRGeometryFactory::createFromWkt(spec.wkt.c_str(), nullptr, &geometry) == OGRERR_NONE,
          "wkt " + spec.wkt);
      feature.SetGeometryDirectly(geometry);
    }
    require(layer->CreateFeature(&feature) == OGRERR_NONE, "feature in " + path);
  }
}

Heightfield small_utm_grid() {
  GeneratedTerrain params;
  params.width = 100;
  params.height = 100;
  params.pixel_size = 10.0;
  return generate_heightfield(params);
}

std::array<double, 2> utm31_from_lon_lat(double lon, double lat) {
  int zone = 31;
  bool north = true;
  double x = 0.0;
  double y = 0.0;
  GeographicLib::UTMUPS::Forward(lat, lon, zone, north, x, y, 31);
  return {x, y};
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "no tw::Error";
}

}  // namespace tw::test
