// A network class's `lead` (docs/networks.md, "In pipelines"): the exemplar's main bearing is
// turned to the region's long axis, the nearest road or the terrain's contours, as an area
// class's rows are (pipeline/lead.hpp). On the sample DEM and map: each lead gives the bearing it
// says (checked against GDAL and OGR reads of the same files), and the lanes of a lead are the
// lanes of its bearing given as `lead_bearing`; without a road or over flat terrain the long axis
// is followed with a warning; config errors name the key.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "pipeline/config.hpp"
#include "pipeline/methods/network/network_report.hpp"
#include "pipeline/plan.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kLeadDemo = test::source_dir() / "pipelines/demo_network.yaml";
constexpr std::size_t kLanes = 2;  // precedence: rivers, roads, lanes
// The demo's region: 600 m east-west by 400 m north-south.
constexpr double kBox[4] = {291000, 9114000, 291600, 9114400};

WorldPlan lead_plan(const fs::path& dir, std::vector<Override> overrides) {
  overrides.push_back({"output.dir", (dir / "out").string()});
  overrides.push_back({"output.preview", "false"});
  Warnings warnings;
  return plan_world(load_pipeline(kLeadDemo, overrides), {}, warnings);
}

const detail::NetworkClassReport& lanes_report(const WorldPlan& plan) {
  const detail::NetworkClassReport* report = detail::network_class_report(plan.report, kLanes);
  EXPECT_NE(report, nullptr);
  static const detail::NetworkClassReport none;
  return report ? *report : none;
}

// Compass degrees folded to [0, 180): a line's two directions are one bearing.
double folded_compass(double dx, double dy) {
  const double degrees = std::atan2(dx, dy) * 180.0 / std::numbers::pi;
  return std::fmod(degrees + 360.0, 180.0);
}

double bearing_gap(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

// The contours' bearing over the box, from the DEM's pixels read by GDAL: the principal axis of
// the central-difference gradients' structure tensor (pixels whose centre is within a pixel of
// the box), turned a quarter.
double dem_contour_bearing(const fs::path& dem, const double box[4]) {
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  EXPECT_NE(ds, nullptr);
  double gt[6];
  ds->GetGeoTransform(gt);
  const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
  std::vector<float> z(std::size_t(w) * h);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0),
            CE_None);
  double xx = 0, xy = 0, yy = 0;
  for (int row = 1; row + 1 < h; ++row)
    for (int col = 1; col + 1 < w; ++col) {
      const double x = gt[0] + (col + 0.5) * gt[1], y = gt[3] + (row + 0.5) * gt[5];
      if (x < box[0] - gt[1] || x > box[2] + gt[1] || y < box[1] + gt[5] || y > box[3] - gt[5])
        continue;
      const auto at = [&](int c, int r) { return double(z[std::size_t(r) * w + c]); };
      const double gx = (at(col + 1, row) - at(col - 1, row)) / (2 * gt[1]);
      const double gy = (at(col, row + 1) - at(col, row - 1)) / (2 * gt[5]);
      xx += gx * gx, xy += gx * gy, yy += gy * gy;
    }
  const double gradient = 0.5 * std::atan2(2 * xy, xx - yy);
  return folded_compass(-std::sin(gradient), std::cos(gradient));
}

// The bearing of the road segment nearest to the box, from OGR reads of the map's roads.
double nearest_road_bearing(const fs::path& map, const double box[4]) {
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(map.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  EXPECT_NE(ds, nullptr);
  OGRLinearRing ring;
  for (const auto& [x, y] : {std::pair{box[0], box[1]},
                             {box[2], box[1]},
                             {box[2], box[3]},
                             {box[0], box[3]},
                             {box[0], box[1]}})
    ring.addPoint(x, y);
  OGRPolygon polygon;
  polygon.addRing(&ring);
  double best = INFINITY, bearing = 0.0;
  for (const auto& feature : ds->GetLayerByName("roads")) {
    const OGRLineString* line = feature->GetGeometryRef()->toLineString();
    for (int i = 0; i + 1 < line->getNumPoints(); ++i) {
      OGRLineString segment;
      segment.addPoint(line->getX(i), line->getY(i));
      segment.addPoint(line->getX(i + 1), line->getY(i + 1));
      const double d = segment.Distance(&polygon);
      if (d < best)
        best = d, bearing = folded_compass(line->getX(i + 1) - line->getX(i),
                                           line->getY(i + 1) - line->getY(i));
    }
  }
  return bearing;
}

TEST(NetworkLead, EachLeadIsItsBearingOverTheRegionOnTheSampleDemAndMap) {
  test::TempDir dir;
  const WorldPlan drawn = lead_plan(dir.path(), {});
  EXPECT_EQ(lanes_report(drawn).lead, "");
  const std::map<std::string, double> expected = {
      {"long_axis", 90.0},  // the box is wider east-west
      {"contours", dem_contour_bearing(test::source_dir() / "samples/dem.tif", kBox)},
      {"nearest_road", nearest_road_bearing(test::source_dir() / "samples/map.gpkg", kBox)}};
  for (const auto& [lead, bearing] : expected) {
    SCOPED_TRACE(lead);
    const WorldPlan plan = lead_plan(dir.path(), {{"features.lanes.network.lead", lead}});
    const detail::NetworkClassReport& report = lanes_report(plan);
    EXPECT_EQ(report.lead, lead);
    // The contours from bilinear samples inside the box against GDAL's pixels around it.
    EXPECT_LT(bearing_gap(report.lead_bearing_deg, bearing), lead == "contours" ? 10.0 : 1e-6)
        << report.lead_bearing_deg << " vs " << bearing;
    // The lead's lanes are those of its bearing given, and not those drawn.
    const WorldPlan given = lead_plan(
        dir.path(),
        {{"features.lanes.network.lead_bearing", fmt::format("{:.17g}", report.lead_bearing_deg)}});
    ASSERT_EQ(plan.lines.at(kLanes).size(), given.lines.at(kLanes).size());
    for (std::size_t i = 0; i < plan.lines[kLanes].size(); ++i)
      EXPECT_EQ(plan.lines[kLanes][i].points, given.lines[kLanes][i].points) << i;
    EXPECT_NE(plan.lines[kLanes].front().points, drawn.lines.at(kLanes).front().points);
  }
  // `lead: { bearing }` is `lead_bearing`.
  const WorldPlan fixed = lead_plan(dir.path(), {{"features.lanes.network.lead", "{bearing: 30}"}});
  EXPECT_EQ(lanes_report(fixed).lead, "bearing");
  EXPECT_EQ(lanes_report(fixed).lead_bearing_deg, 30.0);
  const WorldPlan given = lead_plan(dir.path(), {{"features.lanes.network.lead_bearing", "30"}});
  EXPECT_EQ(fixed.lines.at(kLanes).front().points, given.lines.at(kLanes).front().points);
}

// A small world of its own: no road class, a plane rising eastward or flat ground.
WorldPlan plane_plan(const fs::path& dir, test::DemSpec::Surface surface, const std::string& lead,
                     Warnings& warnings) {
  test::write_dem(dir / "ground.tif", {.width = 80, .height = 80, .surface = surface});
  fs::copy_file(test::source_dir() / "tests/data/network_drawn.svg", dir / "drawn.svg",
                fs::copy_options::overwrite_existing);
  // A box 500 m east-west by 300 m north-south in the DEM (500000..500800, 5000640-800..).
  const PipelineConfig config = parse_pipeline(fmt::format(R"(
version: 1
heightfield: ground.tif
output: {{ dir: out, preview: false }}
features:
  lanes:
    kind: road
    width: 4
    network:
      exemplar: drawn.svg
      scale: 0.5
      region: [500100, 5000100, 500600, 5000400]
      lead: {}
)",
                                                           lead),
                                               "c.yaml", dir);
  return plan_world(config, {}, warnings);
}

bool has_warning(const Warnings& warnings, const std::string& code) {
  for (const Warning& w : warnings.list())
    if (w.code == code) return true;
  return false;
}

TEST(NetworkLead, ContoursOfAPlaneAndTheLongAxisWhereTheLeadHasNothingToFollow) {
  test::TempDir dir;
  using Surface = test::DemSpec::Surface;
  {
    Warnings warnings;
    const WorldPlan plan = plane_plan(dir.path(), Surface::plane_east, "contours", warnings);
    const auto* report = detail::network_class_report(plan.report, 0);
    ASSERT_NE(report, nullptr);
    EXPECT_LT(bearing_gap(report->lead_bearing_deg, 0.0), 1e-6);  // contours run north-south
    EXPECT_FALSE(has_warning(warnings, "network_flat"));
  }
  {
    Warnings warnings;
    const WorldPlan plan = plane_plan(dir.path(), Surface::flat, "contours", warnings);
    const auto* report = detail::network_class_report(plan.report, 0);
    ASSERT_NE(report, nullptr);
    EXPECT_LT(bearing_gap(report->lead_bearing_deg, 90.0), 1e-6);  // the box's long axis
    EXPECT_TRUE(has_warning(warnings, "network_flat"));
  }
  {
    Warnings warnings;
    const WorldPlan plan = plane_plan(dir.path(), Surface::plane_east, "nearest_road", warnings);
    const auto* report = detail::network_class_report(plan.report, 0);
    ASSERT_NE(report, nullptr);
    EXPECT_LT(bearing_gap(report->lead_bearing_deg, 90.0), 1e-6);
    EXPECT_TRUE(has_warning(warnings, "network_no_road"));
  }
}

TEST(NetworkLead, BadLeadsNameTheKey) {
  test::TempDir dir;
  const auto message = [&](std::vector<Override> overrides) {
    try {
      lead_plan(dir.path(), std::move(overrides));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message({{"features.lanes.network.lead", "nearest_raod"}}),
              HasSubstr("features.lanes.network.lead: unknown lead 'nearest_raod', expected "
                        "long_axis, nearest_road, contours or { bearing: DEG } (did you mean "
                        "'nearest_road'?)"));
  EXPECT_THAT(message({{"features.lanes.network.lead", "{bearing: x}"}}),
              HasSubstr("features.lanes.network.lead.bearing"));
  const std::string both = message(
      {{"features.lanes.network.lead", "contours"}, {"features.lanes.network.lead_bearing", "30"}});
  EXPECT_THAT(both, HasSubstr("features.lanes.network.lead_bearing"));
  EXPECT_THAT(both, HasSubstr("not both"));
}

}  // namespace
}  // namespace tw
