#include "gdal_reference.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogr_spatialref.h>

#include <memory>
#include <stdexcept>

namespace tw::test {

Raster<std::uint8_t> gdal_rasterize(const std::vector<Polygon>& polygons, const GridSpec& grid,
                                    const std::string& crs) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  std::unique_ptr<GDALDataset> ds(mem->Create("", grid.width, grid.height, 1, GDT_Byte, nullptr));
  auto gt = grid.geotransform();
  ds->SetGeoTransform(gt.data());
  OGRSpatialReference srs;
  srs.SetFromUserInput(crs.c_str());
  ds->SetSpatialRef(&srs);

  std::vector<OGRGeometryH> geometries;
  for (const Polygon& polygon : polygons) {
    OGRGeometryH g = OGR_G_CreateGeometry(wkbPolygon);
    for (const Ring& ring : polygon) {
      OGRGeometryH r = OGR_G_CreateGeometry(wkbLinearRing);
      for (const Vec2 p : ring) OGR_G_AddPoint_2D(r, p.x, p.y);
      if (!ring.empty() && ring.front() != ring.back())
        OGR_G_AddPoint_2D(r, ring.front().x, ring.front().y);
      OGR_G_AddGeometryDirectly(g, r);
    }
    geometries.push_back(g);
  }
  int band = 1;
  std::vector<double> burn(geometries.size(), 1.0);
  const CPLErr err = GDALRasterizeGeometries(GDALDataset::ToHandle(ds.get()), 1, &band,
                                             int(geometries.size()), geometries.data(), nullptr,
                                             nullptr, burn.data(), nullptr, nullptr, nullptr);
  for (OGRGeometryH g : geometries) OGR_G_DestroyGeometry(g);
  if (err != CE_None) throw std::runtime_error("GDALRasterizeGeometries failed");
  Raster<std::uint8_t> out(grid.width, grid.height, 0);
  if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, grid.width, grid.height, out.pixels.data(),
                                     grid.width, grid.height, GDT_Byte, 0, 0) != CE_None)
    throw std::runtime_error("RasterIO failed");
  return out;
}

double agreement(const Raster<std::uint8_t>& a, const Raster<std::uint8_t>& b) {
  if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 0.0;
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    same += (a.pixels[i] != 0) == (b.pixels[i] != 0);
  return double(same) / double(a.pixels.size());
}

}  // namespace tw::test
