#include "test_world.hpp"

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>
#include <set>

namespace tw::test {

namespace fs = std::filesystem;

void write_dem(const fs::path& path, const DemSpec& spec) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(driver, nullptr);
  std::unique_ptr<GDALDataset> ds(
      driver->Create(path.c_str(), spec.width, spec.height, 1, GDT_Float32, nullptr));
  ASSERT_NE(ds, nullptr);
  double gt[6] = {spec.origin_x, spec.pixel_size, 0, spec.origin_y, 0, -spec.pixel_size};
  ds->SetGeoTransform(gt);
  if (!spec.crs.empty()) {
    OGRSpatialReference srs;
    srs.SetFromUserInput(spec.crs.c_str());
    ds->SetSpatialRef(&srs);
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (spec.nodata) band->SetNoDataValue(*spec.nodata);
  std::vector<float> heights(std::size_t(spec.width) * spec.height);
  for (int y = 0; y < spec.height; ++y) {
    for (int x = 0; x < spec.width; ++x) {
      double z = 100.0 + 50.0 * x / spec.width + 25.0 * std::sin(0.2 * x) * std::cos(0.15 * y);
      if (spec.surface == DemSpec::Surface::plane_east) z = 100.0 + 2.0 * x;
      if (spec.surface == DemSpec::Surface::flat) z = 100.0;
      heights[std::size_t(y) * spec.width + x] = spec.all_nodata ? float(*spec.nodata) : float(z);
    }
  }
  ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, spec.width, spec.height, heights.data(), spec.width,
                           spec.height, GDT_Float32, 0, 0),
            CE_None);
}

void write_layer(const fs::path& path, const std::string& layer_name,
                 const std::vector<VectorFeature>& features, const std::string& crs) {
  GDALAllRegister();
  const char* driver = path.extension() == ".shp" ? "ESRI Shapefile" : "GPKG";
  std::unique_ptr<GDALDataset> ds(
      fs::exists(path) ? GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE)
                       : GetGDALDriverManager()->GetDriverByName(driver)->Create(
                             path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  ASSERT_NE(ds, nullptr) << path;
  OGRSpatialReference srs;
  if (!crs.empty()) srs.SetFromUserInput(crs.c_str());
  OGRLayer* layer =
      ds->CreateLayer(layer_name.c_str(), crs.empty() ? nullptr : &srs, wkbUnknown, nullptr);
  ASSERT_NE(layer, nullptr);
  OGRFieldDefn width("width", OFTReal);
  ASSERT_EQ(layer->CreateField(&width), OGRERR_NONE);
  std::set<std::string> columns;
  for (const VectorFeature& f : features)
    for (const auto& entry : f.text) columns.insert(entry.first);
  for (const std::string& name : columns) {
    OGRFieldDefn column(name.c_str(), OFTString);
    ASSERT_EQ(layer->CreateField(&column), OGRERR_NONE);
  }
  for (const VectorFeature& f : features) {
    OGRFeature feature(layer->GetLayerDefn());
    if (f.wkt.empty()) {
      OGRLineString line;
      for (const auto& [x, y] : f.points) line.addPoint(x, y);
      feature.SetGeometry(&line);
    } else {
      OGRGeometry* geometry = nullptr;
      ASSERT_EQ(OGRGeometryFactory::createFromWkt(f.wkt.c_str(), nullptr, &geometry), OGRERR_NONE)
          << f.wkt;
      feature.SetGeometryDirectly(geometry);
    }
    if (f.width) feature.SetField("width", *f.width);
    for (const auto& [key, value] : f.text) feature.SetField(key.c_str(), value.c_str());
    ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
  }
}

void crop_raster(const fs::path& src, const fs::path& dst, const char* format, int width,
                 int height) {
  GDALAllRegister();
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  ASSERT_NE(in, nullptr) << src;
  const std::string w = std::to_string(width), h = std::to_string(height);
  const char* args[] = {"-of", format, "-srcwin", "0", "0", w.c_str(), h.c_str(), nullptr};
  GDALTranslateOptions* options = GDALTranslateOptionsNew(const_cast<char**>(args), nullptr);
  GDALDatasetH out = GDALTranslate(dst.c_str(), in, options, nullptr);
  GDALTranslateOptionsFree(options);
  ASSERT_NE(out, nullptr) << dst;
  GDALClose(out);
  GDALClose(in);
}

}  // namespace tw::test
