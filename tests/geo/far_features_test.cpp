// Features far beyond the heightfield's CRS domain (docs/pipeline.md, "Features far away"):
// real country-scale data over small UTM 25S DEMs near Olinda. Clipped in their own CRS before
// they are transformed, so a far part never fails a run nor lands on the grid as garbage.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>

#include "geo/features.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

const std::string kLand = (test::source_dir() / "tests/data/dcw_americas.geojson").string();
const std::string kBorders = (test::source_dir() / "tests/data/gshhg_borders.geojson").string();

std::unique_ptr<OGRGeometry> land_geometry() {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> data(GDALDataset::Open(kLand.c_str(), GDAL_OF_VECTOR));
  OGRFeatureUniquePtr feature(data->GetLayer(0)->GetNextFeature());
  return std::unique_ptr<OGRGeometry>(feature->GetGeometryRef()->clone());
}

OGRSpatialReference traditional(int epsg) {
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

// A 100 x 100 DEM of 30 m cells (UTM 25S) centred on the land polygon's coast vertex nearest
// Olinda: the coast crosses it, land on one side, sea on the other.
std::string coast_dem(const test::TempDir& dir, GridSpec& grid) {
  const std::unique_ptr<OGRGeometry> land = land_geometry();
  const OGRLinearRing& ring = *land->toMultiPolygon()->getGeometryRef(0)->getExteriorRing();
  double best = HUGE_VAL, lon = 0.0, lat = 0.0;
  for (int i = 0; i < ring.getNumPoints(); ++i) {
    const double d = std::hypot(ring.getX(i) + 34.85, ring.getY(i) + 8.0);
    if (d < best) best = d, lon = ring.getX(i), lat = ring.getY(i);
  }
  OGRSpatialReference wgs84 = traditional(4326), utm = traditional(31985);
  std::unique_ptr<OGRCoordinateTransformation> to_utm(
      OGRCreateCoordinateTransformation(&wgs84, &utm));
  double x = lon, y = lat;
  to_utm->Transform(1, &x, &y);
  test::DemSpec spec;
  spec.width = spec.height = 100;
  spec.geotransform = {std::round(x / 30) * 30 - 1500, 30, 0,
                       std::round(y / 30) * 30 + 1500, 0,  -30};
  spec.crs = "EPSG:31985";
  const std::string path = (dir / "coast.tif").string();
  test::write_geotiff(path, spec);
  grid = {100, 100, spec.geotransform[0], spec.geotransform[3], 30, 30};
  return path;
}

// The reference: the land cut to the DEM's footprint in lon/lat (densified), then moved into
// UTM 25S; what read_polygon_features keeps must cover the same area.
double reference_area(const GridSpec& grid) {
  OGRSpatialReference wgs84 = traditional(4326), utm = traditional(31985);
  std::unique_ptr<OGRCoordinateTransformation> to_lonlat(
      OGRCreateCoordinateTransformation(&utm, &wgs84));
  std::unique_ptr<OGRCoordinateTransformation> to_utm(
      OGRCreateCoordinateTransformation(&wgs84, &utm));
  OGRLinearRing ring;
  const double w = grid.origin_x, n = grid.origin_y, e = w + grid.width * grid.pixel_width,
               s = n - grid.height * grid.pixel_height;
  ring.addPoint(w, s), ring.addPoint(e, s), ring.addPoint(e, n), ring.addPoint(w, n);
  ring.closeRings();
  OGRPolygon footprint;
  footprint.addRing(&ring);
  footprint.segmentize(10.0);
  footprint.transform(to_lonlat.get());
  std::unique_ptr<OGRGeometry> inside(land_geometry()->Intersection(&footprint));
  inside->transform(to_utm.get());
  // The intersection is a Polygon or a MultiPolygon: both are surfaces with an area.
  return OGR_G_Area(OGRGeometry::ToHandle(inside.get()));
}

double area_of(const std::vector<PolygonFeature>& polygons) {
  double total = 0.0;
  for (const PolygonFeature& p : polygons) {
    for (std::size_t r = 0; r < p.rings.size(); ++r) {
      double twice = 0.0;
      const std::vector<Vec2>& ring = p.rings[r];
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        twice += a.x * b.y - b.x * a.y;
      }
      total += (r == 0 ? 1.0 : -1.0) * std::abs(twice) / 2.0;
    }
  }
  return total;
}

bool inside(const GridSpec& grid, Vec2 p, double margin) {
  return p.x >= grid.origin_x - margin &&
         p.x <= grid.origin_x + grid.width * grid.pixel_width + margin &&
         p.y <= grid.origin_y + margin &&
         p.y >= grid.origin_y - grid.height * grid.pixel_height - margin;
}

// A continent reaching Alaska and the Seychelles (88.5 degrees from UTM 25S's central meridian,
// where PROJ has no transverse Mercator) used to fail the read: "Point outside of projection
// domain". Cut first, it gives the coast over the DEM, the same area as the reference.
TEST(FarFeatures, ContinentPolygonIsCutToTheGridBeforeItIsTransformed) {
  const test::TempDir dir;
  GridSpec grid;
  const Heightfield dem = read_heightfield(coast_dem(dir, grid));
  Warnings warnings;
  const std::vector<PolygonFeature> kept =
      read_polygon_features({kLand, "", ""}, dem, "existing.0", warnings);
  ASSERT_GE(kept.size(), 1u);
  for (const PolygonFeature& p : kept) {
    EXPECT_EQ(p.fid, 1);
    for (const auto& ring : p.rings)
      for (const Vec2& v : ring) EXPECT_TRUE(inside(grid, v, 1e-6)) << v.x << " " << v.y;
  }
  const double full = 3000.0 * 3000.0;
  const double area = area_of(kept);
  EXPECT_GT(area, 0.05 * full);  // the coast crosses the DEM: land and sea
  EXPECT_LT(area, 0.95 * full);
  EXPECT_NEAR(area, reference_area(grid), 0.005 * full);
  EXPECT_TRUE(warnings.empty()) << to_string(warnings.list().front());

  // Over samples/dem.tif (inland Olinda) the same polygon covers the whole DEM.
  const Heightfield olinda = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  const std::vector<PolygonFeature> all =
      read_polygon_features({kLand, "", ""}, olinda, "existing.0", warnings);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(
      area_of(all),
      olinda.grid.width * olinda.grid.pixel_width * olinda.grid.height * olinda.grid.pixel_height,
      1.0);
}

// The same coast as a line (the polygon's rings as a MultiLineString) keeps the pieces over the
// DEM and its halo, as long as the reference's; the Seychelles part never gets transformed.
TEST(FarFeatures, ContinentCoastlineIsCutToTheGridBeforeItIsTransformed) {
  const test::TempDir dir;
  GridSpec grid;
  const Heightfield dem = read_heightfield(coast_dem(dir, grid));
  const std::unique_ptr<OGRGeometry> land = land_geometry();
  std::unique_ptr<OGRGeometry> coast(land->Boundary());
  test::write_vector((dir / "coast.gpkg").string(), "GPKG", "coast", "EPSG:4326",
                     {{1,
                       [&] {
                         char* wkt = nullptr;
                         coast->exportToWkt(&wkt);
                         std::string text(wkt);
                         CPLFree(wkt);
                         return text;
                       }(),
                       20.0}});
  LineClassSpec spec;
  spec.name = "coast";
  spec.source = {(dir / "coast.gpkg").string(), "coast", ""};
  spec.width_attribute = "width";
  Warnings warnings;
  const std::vector<LineFeature> lines = read_line_features(spec, dem, warnings);
  ASSERT_GE(lines.size(), 1u);
  double length = 0.0;
  for (const LineFeature& line : lines) {
    EXPECT_EQ(line.fid, 1);
    for (std::size_t i = 0; i < line.points.size(); ++i) {
      EXPECT_TRUE(inside(grid, line.points[i], 10.0 + 1e-6));
      if (i > 0) length += distance(line.points[i - 1], line.points[i]);
    }
  }
  EXPECT_GT(length, 3000.0);  // crosses the 3 km DEM
  EXPECT_LT(length, 3000.0 * 6);
  for (const Warning& w : warnings.list()) EXPECT_NE(w.code, "dropped_part") << to_string(w);
}

// National borders of the world (GSHHG), none near Olinda: nothing kept, nothing failed, and
// the source is said to meet the heightfield yet give nothing.
TEST(FarFeatures, WorldBordersOverASmallDemGiveNothingAndFailNothing) {
  const Heightfield olinda = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  LineClassSpec spec;
  spec.name = "borders";
  spec.source = {kBorders, "", ""};
  spec.default_width = 10.0;
  Warnings warnings;
  EXPECT_TRUE(read_line_features(spec, olinda, warnings).empty());
  const std::optional<std::string> why = why_no_features(spec.source, olinda);
  ASSERT_TRUE(why.has_value());
  EXPECT_THAT(*why, HasSubstr("none of its 574 features lies on the heightfield"));
}

}  // namespace
}  // namespace tw
