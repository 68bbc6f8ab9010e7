#include "geo/heightfield.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "core/error.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::DemSpec;
using test::error_of;
using test::TempDir;
using ::testing::HasSubstr;

// Metres per degree of longitude / latitude on WGS84 from the textbook radii of curvature
// (independent of the code under test, which measures geodesics).
double metres_per_degree_longitude(double lat) {
  constexpr double a = 6378137.0;
  const double e2 = (1.0 / 298.257223563) * (2.0 - 1.0 / 298.257223563);
  const double phi = lat * std::numbers::pi / 180.0;
  return a / std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi)) * std::cos(phi) * std::numbers::pi /
         180.0;
}
double metres_per_degree_latitude(double lat) {
  constexpr double a = 6378137.0;
  const double e2 = (1.0 / 298.257223563) * (2.0 - 1.0 / 298.257223563);
  const double phi = lat * std::numbers::pi / 180.0;
  const double w = std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi));
  return a * (1 - e2) / (w * w * w) * std::numbers::pi / 180.0;
}

// Maps the centre of a heightfield pixel into another CRS (x = lon/easting).
class GridToCrs {
 public:
  GridToCrs(const Heightfield& field, const std::string& crs) : field_(field) {
    from_.importFromWkt(field.crs_wkt.c_str());
    from_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    to_.SetFromUserInput(crs.c_str());
    to_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    transform_.reset(OGRCreateCoordinateTransformation(&from_, &to_));
  }
  Vec2 operator()(int col, int row) const {
    Vec2 p = field_.grid.pixel_centre_world(col, row);
    EXPECT_TRUE(transform_->Transform(1, &p.x, &p.y));
    return p;
  }

 private:
  const Heightfield& field_;
  OGRSpatialReference from_;
  OGRSpatialReference to_;
  std::unique_ptr<OGRCoordinateTransformation> transform_;
};

TEST(ReadHeightfield, MetricNorthUpDemIsReadAsIsWithNodataAsNaN) {
  TempDir dir;
  const std::string path = (dir / "dem.tif").string();
  DemSpec spec;
  spec.width = 12;
  spec.height = 8;
  spec.nodata = -32768.0;
  spec.value = [](int col, int row) {
    return (col == 3 && row == 2) || row == 7 ? -32768.0 : 100.0 + col + 0.5 * row;
  };
  test::write_geotiff(path, spec);

  const Heightfield field = read_heightfield(path);
  EXPECT_EQ(field.grid, (GridSpec{12, 8, 500000.0, 5000000.0, 10.0, 10.0}));
  EXPECT_EQ(field.source, path);
  ASSERT_TRUE(field.nodata_value.has_value());
  EXPECT_EQ(*field.nodata_value, -32768.0);
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromWkt(field.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_STREQ(srs.GetAuthorityCode(nullptr), "32631");
  for (int row = 0; row < 8; ++row) {
    for (int col = 0; col < 12; ++col) {
      if ((col == 3 && row == 2) || row == 7) {
        EXPECT_TRUE(std::isnan(field.height.at(col, row))) << col << "," << row;
      } else {
        EXPECT_FLOAT_EQ(field.height.at(col, row), 100.0f + col + 0.5f * row);
      }
    }
  }
}

TEST(ReadHeightfield, GeographicDemIsWarpedToMetresAtTheSourceResolution) {
  TempDir dir;
  const std::string path = (dir / "geographic.tif").string();
  DemSpec spec;
  spec.width = 100;
  spec.height = 80;
  spec.geotransform = {6.45, 0.001, 0.0, 45.35, 0.0, -0.001};
  spec.crs = "EPSG:4326";
  spec.nodata = -9999.0;
  // One metre per pixel east and south; a nodata block of 20 x 10 pixels.
  const auto height_at = [](double lon, double lat) {
    return 1000.0 + 1000.0 * (lon - 6.45) + 1000.0 * (45.35 - lat);
  };
  spec.value = [&](int col, int row) {
    if (col >= 40 && col < 60 && row >= 30 && row < 40) return -9999.0;
    return height_at(6.45 + (col + 0.5) * 0.001, 45.35 - (row + 0.5) * 0.001);
  };
  test::write_geotiff(path, spec);

  HeightfieldOptions local;
  local.crs = "local";
  const Heightfield field = read_heightfield(path, local);
  const double centre_lat = 45.31;
  EXPECT_NEAR(field.grid.pixel_width, 0.001 * metres_per_degree_longitude(centre_lat), 0.01);
  EXPECT_NEAR(field.grid.pixel_height, 0.001 * metres_per_degree_latitude(centre_lat), 0.01);
  // The footprint (a slightly curved quadrilateral in the TM frame) needs about as many pixels.
  EXPECT_GE(field.grid.width, 100);
  EXPECT_LE(field.grid.width, 103);
  EXPECT_GE(field.grid.height, 80);
  EXPECT_LE(field.grid.height, 83);
  ASSERT_TRUE(field.nodata_value.has_value());
  EXPECT_EQ(*field.nodata_value, -9999.0);
  EXPECT_NE(field.crs_wkt.find("Transverse Mercator"), std::string::npos);

  const GridToCrs to_lon_lat(field, "EPSG:4326");
  // The frame is centred on the DEM: its centre is at (0, 0) metres.
  EXPECT_NEAR(field.grid.origin_x + field.grid.width * field.grid.pixel_width / 2, 0.0,
              2 * field.grid.pixel_width);
  int checked = 0;
  int nodata_inside_block = 0;
  for (int row = 0; row < field.grid.height; ++row) {
    for (int col = 0; col < field.grid.width; ++col) {
      const float h = field.height.at(col, row);
      const Vec2 ll = to_lon_lat(col, row);
      const double src_col = (ll.x - 6.45) / 0.001;
      const double src_row = (45.35 - ll.y) / 0.001;
      const bool well_inside = src_col > 1.5 && src_col < 98.5 && src_row > 1.5 && src_row < 78.5;
      // Centre on a nodata cell (0.2 pixel margin for gdalwarp's approximate transformer).
      const bool in_block = src_col > 40.2 && src_col < 59.8 && src_row > 30.2 && src_row < 39.8;
      const bool near_block = src_col > 38 && src_col < 62 && src_row > 28 && src_row < 42;
      if (in_block) {
        nodata_inside_block += std::isnan(h);
        EXPECT_TRUE(std::isnan(h)) << "hole shrank at " << col << "," << row;
      } else if (well_inside && !near_block) {
        ASSERT_FALSE(std::isnan(h)) << col << "," << row;
        EXPECT_NEAR(h, height_at(ll.x, ll.y), 0.2) << col << "," << row;
        ++checked;
      }
      if (!std::isnan(h)) {
        EXPECT_GT(h, 900.0f) << "nodata mixed in at " << col << "," << row;
      }
    }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_GT(nodata_inside_block, 100);
}

// output.crs: "utm" puts a geographic DEM in the UTM zone of its centre, named by its EPSG
// code, or any projected CRS asked for; a projected DEM keeps its grid unless another CRS is asked.
TEST(ReadHeightfield, OutputCrsIsTheUtmZoneByDefaultOrTheOneAskedFor) {
  TempDir dir;
  const std::string path = (dir / "luxembourg.tif").string();
  DemSpec spec;
  spec.width = 60;
  spec.height = 40;
  spec.geotransform = {6.0, 0.001, 0.0, 49.65, 0.0, -0.001};
  spec.crs = "EPSG:4326";
  spec.value = [](int col, int row) { return 300.0 + col - row; };
  test::write_geotiff(path, spec);
  const auto epsg = [](const Heightfield& f) {
    OGRSpatialReference srs;
    srs.importFromWkt(f.crs_wkt.c_str());
    const char* code = srs.GetAuthorityCode(nullptr);
    return std::string(code ? code : "");
  };
  HeightfieldOptions zone;
  zone.crs = "utm";
  const Heightfield utm = read_heightfield(path, zone);
  EXPECT_EQ(epsg(utm), "32632");  // 6.03 E: zone 32 north
  EXPECT_NEAR(utm.grid.pixel_height, 0.001 * metres_per_degree_latitude(49.63), 0.01);
  // The west edge (6.0 E) is the footprint's westmost easting, at its south-west corner.
  EXPECT_NEAR(utm.grid.origin_x, 283280.0, 100.0);  // gdaltransform: 283280 at 49.61 N
  HeightfieldOptions luref;
  luref.crs = "EPSG:2169";
  const Heightfield lux = read_heightfield(path, luref);
  EXPECT_EQ(epsg(lux), "2169");
  EXPECT_NEAR(lux.grid.origin_x, 67849.0, 100.0);  // gdaltransform: 67849 at 49.61 N
  HeightfieldOptions geographic;
  geographic.crs = "EPSG:4326";
  EXPECT_THROW(read_heightfield(path, geographic), Error);
  EXPECT_EQ(utm_zone_epsg(-3.7, 40.4), "EPSG:32630");
  EXPECT_EQ(utm_zone_epsg(151.2, -33.9), "EPSG:32756");

  // A projected DEM keeps its grid by default, and is warped when another CRS is asked for.
  const std::string projected = (dir / "utm.tif").string();
  DemSpec metric;
  metric.width = 30;
  metric.height = 20;
  metric.geotransform = {300000.0, 10.0, 0.0, 5500000.0, 0.0, -10.0};
  metric.crs = "EPSG:32632";
  metric.value = [](int col, int row) { return 200.0 + col + row; };
  test::write_geotiff(projected, metric);
  const Heightfield kept = read_heightfield(projected);
  EXPECT_EQ(kept.grid, (GridSpec{30, 20, 300000.0, 5500000.0, 10.0, 10.0}));
  HeightfieldOptions same;
  same.crs = "utm";  // its own zone: nothing to warp
  EXPECT_EQ(read_heightfield(projected, same).grid, kept.grid);
  HeightfieldOptions other;
  other.crs = "EPSG:3035";
  EXPECT_EQ(epsg(read_heightfield(projected, other)), "3035");
}

TEST(ReadHeightfield, WarpedGridCoversTheWholeSourceFootprint) {
  // Points along the DEM's edges, mapped into the warped grid's CRS, lie inside its extent:
  // no row or column of data is lost to rounding the pixel count.
  TempDir dir;
  for (const int width : {37, 50, 61, 83}) {
    const std::string path = (dir / fmt::format("edge_{}.tif", width)).string();
    DemSpec spec;
    spec.width = width;
    spec.height = 31;
    spec.geotransform = {6.1166, 1.0 / 120, 0.0, 49.70, 0.0, -1.0 / 120};
    spec.crs = "EPSG:4326";
    test::write_geotiff(path, spec);
    const Heightfield field = read_heightfield(path);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference grid_srs;
    grid_srs.importFromWkt(field.crs_wkt.c_str());
    grid_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> to_grid(
        OGRCreateCoordinateTransformation(&wgs84, &grid_srs));
    const double east = 6.1166 + width / 120.0;
    const double south = 49.70 - 31 / 120.0;
    for (int i = 0; i <= 20; ++i) {
      const double t = i / 20.0;
      for (Vec2 p :
           {Vec2{6.1166 + t * (east - 6.1166), south}, Vec2{6.1166 + t * (east - 6.1166), 49.70},
            Vec2{6.1166, south + t * (49.70 - south)}, Vec2{east, south + t * (49.70 - south)}}) {
        ASSERT_TRUE(to_grid->Transform(1, &p.x, &p.y));
        const Vec2 pixel = field.grid.world_to_pixel(p);
        EXPECT_GE(pixel.x, -1e-6) << width << " " << i;
        EXPECT_GE(pixel.y, -1e-6) << width << " " << i;
        EXPECT_LE(pixel.x, field.grid.width + 1e-6) << width << " " << i;
        EXPECT_LE(pixel.y, field.grid.height + 1e-6) << width << " " << i;
      }
    }
  }
}

TEST(ReadHeightfield, ResolutionOptionOnAGeographicDemSetsThePixelSize) {
  TempDir dir;
  const std::string path = (dir / "geographic.tif").string();
  DemSpec spec;
  spec.width = 50;
  spec.height = 50;
  spec.geotransform = {-3.0, 0.002, 0.0, 40.0, 0.0, -0.002};
  spec.crs = "EPSG:4326";
  test::write_geotiff(path, spec);
  const Heightfield field = read_heightfield(path, {.resolution = 25.0, .crs = {}});
  EXPECT_EQ(field.grid.pixel_width, 25.0);
  EXPECT_EQ(field.grid.pixel_height, 25.0);
  // 50 pixels of 0.002 degrees east-west at ~39.95 N.
  const double extent = 50 * 0.002 * metres_per_degree_longitude(39.95);
  EXPECT_NEAR(field.grid.width * 25.0, extent, 3 * 25.0);
  EXPECT_FALSE(field.nodata_value.has_value());
}

TEST(ReadHeightfield, FeetAreWarpedToMetres) {
  TempDir dir;
  const std::string path = (dir / "feet.tif").string();
  DemSpec spec;
  spec.width = 30;
  spec.height = 30;
  spec.geotransform = {2000000.0, 30.0, 0.0, 700000.0, 0.0, -30.0};
  spec.crs = "EPSG:2264";  // NAD83 / North Carolina (ftUS)
  test::write_geotiff(path, spec);
  const Heightfield field = read_heightfield(path);
  const double us_foot = 1200.0 / 3937.0;
  // State-plane scale error is under 1e-4: the pixels are 30 US feet on the ground.
  EXPECT_NEAR(field.grid.pixel_width, 30.0 * us_foot, 0.005);
  EXPECT_NEAR(field.grid.pixel_height, 30.0 * us_foot, 0.005);
  EXPECT_NE(field.crs_wkt.find("Transverse Mercator"), std::string::npos);
  EXPECT_FLOAT_EQ(field.height.at(field.grid.width / 2, field.grid.height / 2), 100.0f);
}

TEST(ReadHeightfield, RotatedGeotransformIsWarpedNorthUp) {
  TempDir dir;
  const std::string path = (dir / "rotated.tif").string();
  const double angle = 30.0 * std::numbers::pi / 180.0;
  DemSpec spec;
  spec.width = 40;
  spec.height = 40;
  const double c = 10.0 * std::cos(angle);
  const double s = 10.0 * std::sin(angle);
  spec.geotransform = {500000.0, c, s, 5000000.0, s, -c};
  const auto height_at = [](double x, double y) {
    return 200.0 + 0.05 * (x - 500000.0) + 0.02 * (5000000.0 - y);
  };
  spec.value = [&](int col, int row) {
    const double u = col + 0.5;
    const double v = row + 0.5;
    return height_at(500000.0 + u * c + v * s, 5000000.0 + u * s - v * c);
  };
  test::write_geotiff(path, spec);

  const Heightfield field = read_heightfield(path);
  // UTM's scale at its central meridian is 0.9996: 10 grid metres are 10.004 on the ground.
  EXPECT_NEAR(field.grid.pixel_width, 10.0 / 0.9996, 0.01);
  EXPECT_NEAR(field.grid.pixel_height, 10.0 / 0.9996, 0.01);
  // A 40-pixel square turned by 30 degrees needs about 40 (cos 30 + sin 30) = 55 pixels.
  EXPECT_NEAR(field.grid.width, 55, 2);
  const GridToCrs to_utm(field, "EPSG:32631");
  int checked = 0;
  for (int row = 0; row < field.grid.height; ++row) {
    for (int col = 0; col < field.grid.width; ++col) {
      const Vec2 p = to_utm(col, row);
      const double dx = p.x - 500000.0;
      const double dy = p.y - 5000000.0;
      const double u = (dx * c + dy * s) / 100.0;  // source pixel coordinates
      const double v = (dx * s - dy * c) / 100.0;
      const float h = field.height.at(col, row);
      if (u > 1.5 && u < 38.5 && v > 1.5 && v < 38.5) {
        ASSERT_FALSE(std::isnan(h));
        EXPECT_NEAR(h, height_at(p.x, p.y), 0.1) << col << "," << row;
        ++checked;
      } else if (u < -1.0 || u > 41.0 || v < -1.0 || v > 41.0) {
        EXPECT_TRUE(std::isnan(h)) << "outside the source at " << col << "," << row;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(ReadHeightfield, ResolutionOptionResamplesAMetricDemWithoutMixingNodata) {
  TempDir dir;
  const std::string path = (dir / "metric.tif").string();
  DemSpec spec;
  spec.width = 40;
  spec.height = 40;
  spec.nodata = -9999.0;
  const auto height_at = [](double x, double y) {
    return 50.0 + 0.05 * (x - 500000.0) + 0.02 * (5000000.0 - y);
  };
  spec.value = [&](int col, int row) {
    if (col == 10 && row == 10) return -9999.0;
    return height_at(500000.0 + (col + 0.5) * 10.0, 5000000.0 - (row + 0.5) * 10.0);
  };
  test::write_geotiff(path, spec);

  const Heightfield field = read_heightfield(path, {.resolution = 20.0, .crs = {}});
  EXPECT_EQ(field.grid, (GridSpec{20, 20, 500000.0, 5000000.0, 20.0, 20.0}));
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromWkt(field.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_STREQ(srs.GetAuthorityCode(nullptr), "32631");
  for (int row = 0; row < 20; ++row) {
    for (int col = 0; col < 20; ++col) {
      const float h = field.height.at(col, row);
      const Vec2 p = field.grid.pixel_centre_world(col, row);
      const bool near_hole = std::abs(col - 5) <= 1 && std::abs(row - 5) <= 1;
      if (!near_hole && col > 0 && row > 0 && col < 19 && row < 19) {
        EXPECT_NEAR(h, height_at(p.x, p.y), 1e-3) << col << "," << row;
      } else if (!std::isnan(h)) {
        // Next to the hole only valid neighbours count: still a plausible height.
        EXPECT_NEAR(h, height_at(p.x, p.y), 1.0) << "nodata mixed in at " << col << "," << row;
      }
    }
  }
}

// Cubic resampling (Catmull-Rom) reproduces a quadratic terrain that bilinear reads with the
// sag h^2 z'' / 8 between cells, keeps nodata out and keeps holes as they were.
TEST(ReadHeightfield, CubicResamplingFollowsCurvedTerrainAndKeepsNodataOut) {
  TempDir dir;
  const std::string path = (dir / "curved.tif").string();
  DemSpec spec;
  spec.width = 40;
  spec.height = 40;
  spec.nodata = -9999.0;
  const auto height_at = [](double x, double y) {
    const double u = x - 500200.0, v = 4999800.0 - y;
    return 100.0 + 0.002 * u * u + 0.001 * v * v;
  };
  spec.value = [&](int col, int row) {
    if (col >= 30 && col < 33 && row >= 30 && row < 33) return -9999.0;
    return height_at(500000.0 + (col + 0.5) * 10.0, 5000000.0 - (row + 0.5) * 10.0);
  };
  test::write_geotiff(path, spec);
  double worst[2] = {0.0, 0.0};
  for (const Resampling r : {Resampling::bilinear, Resampling::cubic}) {
    const Heightfield field =
        read_heightfield(path, {.resolution = 2.5, .resampling = r, .crs = {}});
    ASSERT_EQ(field.grid.width, 160);
    int holes = 0;
    for (int row = 0; row < 160; ++row) {
      for (int col = 0; col < 160; ++col) {
        const float h = field.height.at(col, row);
        const Vec2 p = field.grid.pixel_centre_world(col, row);
        const double src_col = (p.x - 500000.0) / 10.0, src_row = (5000000.0 - p.y) / 10.0;
        const bool in_hole = src_col > 30.2 && src_col < 32.8 && src_row > 30.2 && src_row < 32.8;
        const bool near_hole = src_col > 27 && src_col < 36 && src_row > 27 && src_row < 36;
        const bool inside = src_col > 2 && src_col < 38 && src_row > 2 && src_row < 38;
        if (in_hole) {
          holes += std::isnan(h);
          EXPECT_TRUE(std::isnan(h)) << "hole shrank at " << col << "," << row;
        } else if (inside && !near_hole) {
          ASSERT_FALSE(std::isnan(h)) << col << "," << row;
          worst[int(r)] = std::max(worst[int(r)], std::abs(h - height_at(p.x, p.y)));
        }
        if (!std::isnan(h)) {
          EXPECT_GT(h, 90.0f) << "nodata mixed in at " << col << "," << row;
        }
      }
    }
    EXPECT_GT(holes, 50);
    // Along the DEM's edges too, heights change smoothly, not in stairs of whole cells (GDAL's
    // cubic warp went blocky within two cells of the edges).
    for (int row : {0, 1, 158, 159}) {
      for (int col = 0; col + 1 < 160; ++col) {
        const Vec2 a = field.grid.pixel_centre_world(col, row);
        const Vec2 b = field.grid.pixel_centre_world(col + 1, row);
        const double step = std::abs(field.height.at(col + 1, row) - field.height.at(col, row));
        EXPECT_LE(step, 1.5 * std::abs(height_at(b.x, b.y) - height_at(a.x, a.y)) + 0.05)
            << "row " << row << " col " << col;
      }
    }
  }
  std::printf(
      "quadratic terrain, 10 m DEM read at 2.5 m: worst error bilinear %.4f m, cubic "
      "%.4f m\n",
      worst[0], worst[1]);
  EXPECT_GT(worst[0], 0.05);   // z'' h^2 / 8 = (0.004 + 0.002) * 10^2 / 8 = 0.075 between 4 cells
  EXPECT_LT(worst[1], 0.005);  // exact on quadratics up to float rounding
}

// Reading a DEM at a coarser resolution averages it (a checkerboard of +-10 m becomes about its
// mean) in both modes, as GDAL's warper does, instead of picking every third cell.
TEST(ReadHeightfield, CoarserResolutionAveragesInsteadOfAliasing) {
  TempDir dir;
  const std::string path = (dir / "checkerboard.tif").string();
  DemSpec spec;
  spec.width = 40;
  spec.height = 40;
  spec.value = [](int col, int row) { return (col + row) % 2 ? 90.0 : 110.0; };
  test::write_geotiff(path, spec);
  for (const Resampling r : {Resampling::bilinear, Resampling::cubic}) {
    // 30 m cells: their centres fall on source cell centres, where a point read gives 90 or 110;
    // the mean of 3 x 3 cells is within 20 / 9 of 100.
    const Heightfield field =
        read_heightfield(path, {.resolution = 30.0, .resampling = r, .crs = {}});
    ASSERT_EQ(field.grid, (GridSpec{14, 14, 500000.0, 5000000.0, 30.0, 30.0}));
    for (int row = 0; row < 13; ++row)  // the 14th row and column reach past the DEM
      for (int col = 0; col < 13; ++col)
        EXPECT_NEAR(field.height.at(col, row), 100.0f, 2.5f) << int(r) << " " << col << "," << row;
  }
}

TEST(ReadHeightfield, ReadsBandOneOfAMultiBandDem) {
  TempDir dir;
  for (const std::string crs : {"EPSG:32631", "EPSG:4326"}) {
    const std::string path = (dir / "bands.tif").string();
    DemSpec spec;
    spec.bands = 3;
    spec.crs = crs;
    if (crs == "EPSG:4326") spec.geotransform = {3.0, 0.0001, 0.0, 45.0, 0.0, -0.0001};
    test::write_geotiff(path, spec);
    const Heightfield field = read_heightfield(path);
    EXPECT_FLOAT_EQ(field.height.at(field.grid.width / 2, field.grid.height / 2), 100.0f) << crs;
  }
}

TEST(ReadHeightfield, HeightsInFeetBecomeMetres) {
  TempDir dir;
  const std::string path = (dir / "feet_heights.tif").string();
  DemSpec spec;
  spec.unit = "ft";
  spec.nodata = -9999.0;
  spec.value = [](int col, int) { return col == 0 ? -9999.0 : 1000.0; };
  test::write_geotiff(path, spec);
  const Heightfield field = read_heightfield(path);
  EXPECT_FLOAT_EQ(field.height.at(5, 5), 304.8f);
  EXPECT_TRUE(std::isnan(field.height.at(0, 5)));
  EXPECT_EQ(*field.nodata_value, -9999.0);
}

TEST(ReadHeightfield, AnUnknownHeightUnitIsTakenAsMetresWithAWarning) {
  TempDir dir;
  const std::string path = (dir / "fathoms.tif").string();
  DemSpec spec;
  spec.unit = "fathom";
  test::write_geotiff(path, spec);
  Warnings warnings;
  const Heightfield field = read_heightfield(path, {}, warnings);
  EXPECT_FLOAT_EQ(field.height.at(5, 5), 100.0f);
  ASSERT_EQ(warnings.size(), 1u);
  const Warning w = warnings.list()[0];
  EXPECT_EQ(w.code, "unknown_unit");
  EXPECT_EQ(w.subject, "heightfield");
  EXPECT_FALSE(w.fid.has_value());
  EXPECT_THAT(w.message, AllOf(HasSubstr("fathoms.tif"), HasSubstr("'fathom'")));
}

TEST(ReadHeightfield, AllNodataIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string path = (dir / "empty_dem.tif").string();
  DemSpec spec;
  spec.nodata = -1.0;
  spec.value = [](int, int) { return -1.0; };
  test::write_geotiff(path, spec);
  EXPECT_THAT(error_of([&] { read_heightfield(path); }),
              AllOf(HasSubstr("empty_dem.tif"), HasSubstr("nodata")));
}

TEST(ReadHeightfield, MissingCrsIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string path = (dir / "no_crs.tif").string();
  DemSpec spec;
  spec.crs.clear();
  test::write_geotiff(path, spec);
  EXPECT_THAT(error_of([&] { read_heightfield(path); }),
              AllOf(HasSubstr("no_crs.tif"), HasSubstr("CRS")));
}

TEST(ReadHeightfield, MissingOrUnreadableFileIsAnErrorNamingTheFile) {
  TempDir dir;
  EXPECT_THAT(error_of([&] { read_heightfield((dir / "absent.tif").string()); }),
              HasSubstr("absent.tif"));
  const std::string text = (dir / "not_a_raster.tif").string();
  std::FILE* file = std::fopen(text.c_str(), "w");
  std::fputs("hello", file);
  std::fclose(file);
  EXPECT_THAT(error_of([&] { read_heightfield(text); }), HasSubstr("not_a_raster.tif"));
}

TEST(ReadHeightfield, NonPositiveResolutionIsAnError) {
  TempDir dir;
  const std::string path = (dir / "dem.tif").string();
  test::write_geotiff(path, DemSpec{});
  EXPECT_THAT(error_of([&] { read_heightfield(path, {.resolution = 0.0, .crs = {}}); }),
              AllOf(HasSubstr("dem.tif"), HasSubstr("resolution")));
}

}  // namespace
}  // namespace tw
