// A line class grown as a curve network inside a run (docs/networks.md, "In pipelines";
// pipelines/demo_network.yaml on the sample DEM): its lines are the class's features in
// features.geojson, never cross (GEOS), lie in the region and off the roads read before them,
// are painted in the class's splat material and forbidden in the avoidance layer, are the same
// bytes for the same seed, and a tiled run equals the untiled one; config errors name the key.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cache_world.hpp"
#include "core/error.hpp"
#include "pipeline/methods/network/network_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kDemo = test::source_dir() / "pipelines/demo_network.yaml";
constexpr double kRegion[4] = {291000, 9114000, 291600, 9114400};

PipelineConfig demo(const fs::path& out, std::vector<Override> overrides = {}) {
  overrides.push_back({"output.dir", out.string()});
  overrides.push_back({"output.preview", "false"});
  return load_pipeline(kDemo, overrides);
}

struct ClassLine {
  std::unique_ptr<OGRLineString> line;
  double width = 0.0;
};

std::vector<ClassLine> class_lines(const fs::path& out, const std::string& name) {
  GDALAllRegister();
  std::vector<ClassLine> lines;
  GDALDatasetUniquePtr ds(
      GDALDataset::Open((out / "features.geojson").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  EXPECT_NE(ds, nullptr);
  if (!ds) return lines;
  for (const auto& feature : ds->GetLayer(0)) {
    if (std::string(feature->GetFieldAsString("class")) != name) continue;
    lines.push_back(
        {std::unique_ptr<OGRLineString>(feature->GetGeometryRef()->toLineString()->clone()),
         feature->GetFieldAsDouble("width")});
  }
  return lines;
}

// Every band of a raster as floats, band after band, with its geotransform.
std::vector<float> pixels(const fs::path& path, int* width = nullptr, int* height = nullptr,
                          double* transform = nullptr) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  EXPECT_NE(ds, nullptr) << path;
  if (!ds) return {};
  const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
  if (width) *width = w;
  if (height) *height = h;
  if (transform) ds->GetGeoTransform(transform);
  std::vector<float> out(std::size_t(w) * h * ds->GetRasterCount());
  for (int b = 0; b < ds->GetRasterCount(); ++b)
    EXPECT_EQ(
        ds->GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, w, h, out.data() + std::size_t(w) * h * b,
                                           w, h, GDT_Float32, 0, 0),
        CE_None);
  return out;
}

int band_named(const fs::path& path, const std::string& name) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) return -1;
  for (int b = 1; b <= ds->GetRasterCount(); ++b)
    if (name == ds->GetRasterBand(b)->GetDescription()) return b - 1;
  return -1;
}

std::int64_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::int64_t(std::max(a.size(), b.size()));
  std::int64_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return n;
}

TEST(NetworkRun, LanesAreTheClassLinesInTheRegionOffTheRoadsAndInTheLayers) {
  test::TempDir dir;
  const RunReport report = run_pipeline(demo(dir / "a"));
  const std::vector<ClassLine> lanes = class_lines(dir / "a", "lanes");
  ASSERT_GE(lanes.size(), 8u);
  const auto c = std::find_if(report.classes.begin(), report.classes.end(),
                              [](const FeatureClassReport& r) { return r.name == "lanes"; });
  ASSERT_NE(c, report.classes.end());
  EXPECT_EQ(c->features.size(), lanes.size());
  OGRPolygon region;
  {
    OGRLinearRing ring;
    ring.addPoint(kRegion[0], kRegion[1]);
    ring.addPoint(kRegion[2], kRegion[1]);
    ring.addPoint(kRegion[2], kRegion[3]);
    ring.addPoint(kRegion[0], kRegion[3]);
    ring.closeRings();
    region.addRing(&ring);
  }
  std::unique_ptr<OGRGeometry> inside(region.Buffer(1e-6));
  const auto is_end = [](const OGRLineString& l, const OGRPoint& p) {
    OGRPoint a, b;
    l.StartPoint(&a);
    l.EndPoint(&b);
    return a.Distance(&p) < 1e-6 || b.Distance(&p) < 1e-6;
  };
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    const OGRLineString& a = *lanes[i].line;
    EXPECT_DOUBLE_EQ(lanes[i].width, 4.0);
    EXPECT_TRUE(inside->Contains(&a)) << "lane " << i;
    // Two lanes meet only where both end (a junction), never elsewhere.
    for (std::size_t j = i + 1; j < lanes.size(); ++j) {
      const OGRLineString& b = *lanes[j].line;
      if (!a.Intersects(&b)) continue;
      std::unique_ptr<OGRGeometry> common(a.Intersection(&b));
      const auto check = [&](const OGRPoint& p) {
        EXPECT_TRUE(is_end(a, p) && is_end(b, p))
            << "lanes " << i << " and " << j << " cross at " << p.getX() << " " << p.getY();
      };
      const auto type = wkbFlatten(common->getGeometryType());
      ASSERT_TRUE(type == wkbPoint || type == wkbMultiPoint) << "lanes " << i << " and " << j;
      if (type == wkbPoint)
        check(*common->toPoint());
      else
        for (const OGRPoint* p : *common->toMultiPoint()) check(*p);
    }
    // Off the roads read before them: their footprints (half widths) do not overlap, up to the
    // forbidden cells' resolution (1 m cells over this region: half a diagonal).
    for (const ClassLine& road : class_lines(dir / "a", "roads"))
      EXPECT_GT(a.Distance(road.line.get()), 0.5 * (road.width + 4.0) - 0.75) << "lane " << i;
  }
  // Under the lanes: their material (road) in the splat and the forbidden mask in avoidance.
  int width = 0, height = 0;
  double gt[6];
  const std::vector<float> splat = pixels(dir / "a/splat.tif", &width, &height, gt);
  const std::vector<float> avoidance = pixels(dir / "a/avoidance.tif");
  const int road = band_named(dir / "a/splat.tif", "splat.road");
  const int forbidden = band_named(dir / "a/avoidance.tif", "forbidden");
  ASSERT_GE(road, 0);
  ASSERT_GE(forbidden, 0);
  int samples = 0, painted = 0, masked = 0;
  for (const ClassLine& lane : lanes) {
    const OGRLineString& l = *lane.line;
    const double length = l.get_Length();
    for (double s = 0.5 * 4.0; s < length; s += 4.0) {
      OGRPoint p;
      l.Value(s, &p);
      const int col = int((p.getX() - gt[0]) / gt[1]), row = int((p.getY() - gt[3]) / gt[5]);
      ASSERT_TRUE(col >= 0 && col < width && row >= 0 && row < height);
      const std::size_t at = std::size_t(row) * width + col, band = std::size_t(width) * height;
      ++samples;
      painted += splat[road * band + at] > 0.0f;
      masked += avoidance[forbidden * band + at] > 0.0f;
    }
  }
  std::printf("%zu lanes, %d samples: %d with splat.road > 0, %d forbidden\n", lanes.size(),
              samples, painted, masked);
  ASSERT_GT(samples, 50);
  // report.json: the growth's counts; the roads and existing features rejected some pieces.
  const nlohmann::json json = nlohmann::json::parse(test::read_file(dir / "a/report.json"));
  const auto& network = json["classes"][2]["network"];
  EXPECT_EQ(json["classes"][2]["name"], "lanes");
  EXPECT_EQ(network["lines"].get<std::size_t>(), lanes.size());
  EXPECT_GE(network["exemplar_edges"].get<int>(), 5);
  EXPECT_GT(network["placed"].get<int>(), 0);
  EXPECT_EQ(network["kept"].get<int>(), 0);
  // Which method made the lanes (issue #20): `automatic` as asked, and the one it kept (the
  // layout: with its own pieces' loose ends kept, it meets more of the drawn exemplar's targets
  // than growth, which keeps its gaps too; which one wins moves with either's quality).
  EXPECT_EQ(network["method"], "automatic");
  EXPECT_EQ(network["chosen"], "layout");
  EXPECT_GE(painted, samples * 95 / 100);
  EXPECT_GE(masked, samples * 95 / 100);
}

TEST(NetworkRun, SameSeedSameBytesOtherSeedOtherLanesTiledEqualsUntiled) {
  test::TempDir dir;
  run_pipeline(demo(dir / "a"));
  run_pipeline(demo(dir / "b"));
  for (const char* file : {"features.geojson", "height.tif", "splat.tif", "avoidance.tif"})
    EXPECT_EQ(test::read_file(dir / "a" / file), test::read_file(dir / "b" / file)) << file;
  run_pipeline(demo(dir / "c", {{"features.lanes.network.seed", "8"}}));
  EXPECT_NE(test::read_file(dir / "a/features.geojson"),
            test::read_file(dir / "c/features.geojson"));
  // Tiles of 64 pixels: the network is grown once, in the plan, so every tile sees it.
  run_pipeline(demo(dir / "t", {{"output.tiles.size", "64"}}));
  for (const std::string layer : {"height", "splat", "avoidance"})
    EXPECT_EQ(differing(pixels(dir / "t" / (layer + ".vrt")), pixels(dir / "a" / (layer + ".tif"))),
              0)
        << layer;
  EXPECT_EQ(test::read_file(dir / "a/features.geojson"),
            test::read_file(dir / "t/features.geojson"));
  // A saved plan (what distributed workers load) carries the grown lanes point for point.
  Warnings warnings;
  const WorldPlan plan = plan_world(demo(dir / "p"), {}, warnings);
  save_plan(plan, dir / "plan");
  const WorldPlan loaded = load_plan(dir / "plan");
  const std::size_t lanes = 2;  // precedence: rivers, roads, lanes
  ASSERT_EQ(plan.class_names.at(lanes), "lanes");
  ASSERT_GE(plan.lines.at(lanes).size(), 8u);
  ASSERT_EQ(loaded.lines.at(lanes).size(), plan.lines.at(lanes).size());
  for (std::size_t i = 0; i < plan.lines[lanes].size(); ++i) {
    EXPECT_EQ(loaded.lines[lanes][i].points, plan.lines[lanes][i].points);
    EXPECT_EQ(loaded.lines[lanes][i].fid, std::int64_t(i + 1));
  }
}

// report.json's values but the timings and the pipeline it echoes.
nlohmann::json report_values(const nlohmann::json& j) {
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : j) out.push_back(report_values(v));
    return out;
  }
  if (!j.is_object()) return j;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, v] : j.items())
    if (key != "pipeline" && key != "timings" && key != "stages" && !key.ends_with("seconds"))
      out[key] = report_values(v);
  return out;
}

// A run of `pipeline` by `terraweave run` and as separate processes (docs/distributed.md): plan
// (with --synthesis tasks: synth-feature per feature, then complete-plan), render-tile per tile
// (last first), finish. Every file of the two output folders is the same bytes (report.json: the
// same values but timings); their lanes carry the hedge pattern. Returns the plan's counts.
struct Planned {
  std::size_t tiles = 0, syntheses = 0;
};
Planned expect_distributed_equals_run(const fs::path& dir, const fs::path& pipeline,
                                      const std::string& sets, bool synthesis_tasks) {
  const std::string binary = "'" + test::terraweave_binary().string() + "' -q ";
  const auto step = [&](const std::string& args) {
    const test::CommandResult r = test::run_command(binary + args + " 2>&1");
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.output;
    return r.output;
  };
  step("run " + pipeline.string() + " --out " + (dir / "local").string() + sets);
  const fs::path out = dir / "distributed";
  const std::string planned = step("plan " + pipeline.string() + " --out " + out.string() + sets +
                                   (synthesis_tasks ? " --synthesis tasks" : ""));
  Planned counts;
  const std::size_t at = planned.find("plan ");
  EXPECT_NE(at, std::string::npos) << planned;
  if (at == std::string::npos) return counts;
  EXPECT_EQ(std::sscanf(planned.substr(at).c_str(), "plan %*s %zu tiles, %zu syntheses to run",
                        &counts.tiles, &counts.syntheses),
            2)
      << planned;
  for (std::size_t f = 0; f < counts.syntheses; ++f)
    step("synth-feature " + out.string() + " --feature " + std::to_string(f));
  if (counts.syntheses > 0) step("complete-plan " + out.string());
  for (std::size_t t = counts.tiles; t-- > 0;)
    step("render-tile " + out.string() + " --tile " + std::to_string(t));
  step("finish " + out.string());

  const auto local = test::output_files(dir / "local");
  const auto distributed = test::output_files(out);
  EXPECT_TRUE(local.contains("features.geojson"));
  EXPECT_GE(class_lines(dir / "local", "lanes").size(), 3u);
  const nlohmann::json local_report =
      nlohmann::json::parse(test::read_file(dir / "local/report.json"));
  int dressed = 0;  // lanes carrying the hedge pattern
  for (const auto& c : local_report["classes"])
    if (c["name"] == "lanes")
      for (const auto& f : c["features"]) dressed += f["pieces"].get<int>() > 0;
  EXPECT_GE(dressed, 3);
  std::vector<std::string> names, other_names;
  for (const auto& [name, bytes] : local) names.push_back(name);
  for (const auto& [name, bytes] : distributed) other_names.push_back(name);
  EXPECT_EQ(names, other_names);
  EXPECT_GE(std::count_if(names.begin(), names.end(),
                          [](const std::string& n) { return n.starts_with("tiles/"); }),
            4);
  EXPECT_EQ(report_values(local_report),
            report_values(nlohmann::json::parse(test::read_file(out / "report.json"))));
  for (const auto& [name, bytes] : local) {
    const auto it = distributed.find(name);
    if (it != distributed.end()) {
      EXPECT_TRUE(bytes == it->second) << name << " differs";
    }
  }
  return counts;
}

// Issue #20: a network class run distributed: the lanes grown once in the plan reach every tile.
// A corner of the demo (a close-up, so its plan synthesizes the lanes' patterns itself): 22
// lanes, 2 x 2 tiles.
TEST(NetworkRun, DistributedStepsWriteTheBytesOfARun) {
  test::TempDir dir;
  const Planned planned = expect_distributed_equals_run(
      dir.path(), kDemo,
      " --set 'region=[290990, 9113990, 291310, 9114210]'"
      " --set 'features.lanes.network.region=[291000, 9114000, 291300, 9114200]'"
      " --set output.tiles.size=48 --set output.tiles.overlap=4 --set output.preview=false"
      " --set features.lanes.synthesis.exemplar=" +
          (test::source_dir() / "samples/exemplars/hedge_192x48.png").string() +
          " --set features.lanes.synthesis.delta=8",
      false);
  EXPECT_EQ(planned.tiles, 4u);      // 81 x 56 pixels
  EXPECT_EQ(planned.syntheses, 0u);  // a close-up synthesizes in the plan
}

// The lanes' syntheses as tasks (synth-feature reads the grown lanes from the plan), on a tiny
// generated world (not a close-up). The synthesis gives no width: the exemplar's, which the tasks
// did not take (they read the pipeline without the exemplars' defaults and drew narrower
// ribbons: other placements than the run's).
TEST(NetworkRun, SynthesisTasksWriteTheBytesOfARun) {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml")
      << "version: 1\nseed: 7\n"
         "generate: { width: 50, height: 40, pixel_size: 4, relief: 20, origin: [500000, "
         "5000160] }\n"
         "output: { exr: false, preview: false, tiles: { size: 32, overlap: 4 } }\n"
         "features:\n  lanes:\n    kind: road\n    width: 4\n"
         "    network: { exemplar: " +
             (test::source_dir() / "tests/data/network_drawn.svg").string() +
             ", scale: 0.5, region: [500010, 5000010, 500150, 5000120] }\n"
             "    synthesis: { exemplar: " +
             (test::source_dir() / "samples/exemplars/hedge_192x48.png").string() +
             ", delta: 8 }\n";
  const Planned planned = expect_distributed_equals_run(dir.path(), dir / "tiny.yaml", "", true);
  EXPECT_EQ(planned.tiles, 4u);
  EXPECT_GE(planned.syntheses, 3u);  // one task per lane
}

TEST(NetworkRun, SynthesisAlongTheLanes) {
  test::TempDir dir;
  run_pipeline(
      demo(dir / "s", {{"features.lanes.synthesis.exemplar",
                        (test::source_dir() / "samples/exemplars/hedge_192x48.png").string()},
                       {"features.lanes.synthesis.delta", "8"}}));
  const nlohmann::json report = nlohmann::json::parse(test::read_file(dir / "s/report.json"));
  EXPECT_EQ(report["pattern_violations"].get<int>(), 0);
  const auto& classes = report["classes"];
  const auto lanes = std::find_if(classes.begin(), classes.end(),
                                  [](const auto& c) { return c["name"] == "lanes"; });
  ASSERT_NE(lanes, classes.end());
  int synthesized = 0, long_enough = 0;
  for (const auto& f : (*lanes)["features"]) {
    if (f["length_m"].get<double>() < 8.0) continue;
    ++long_enough;
    synthesized += f.contains("synthesis") && f["pieces"].get<int>() > 0;
  }
  EXPECT_GE(long_enough, 8);
  EXPECT_EQ(synthesized, long_enough);
  // The pattern's coverage is a splat material of its own.
  int width = 0, height = 0;
  const std::vector<float> splat = pixels(dir / "s/splat.tif", &width, &height);
  const int band = band_named(dir / "s/splat.tif", "splat.lanes_pattern");
  ASSERT_GE(band, 0);
  const std::size_t n = std::size_t(width) * height;
  EXPECT_GT(*std::max_element(splat.begin() + band * n, splat.begin() + (band + 1) * n), 0.5f);
}

// The synthesis cache keys the lines' geometry: a rerun reuses every lane's synthesis, a network
// grown with another seed rebuilds them.
TEST(NetworkRun, CacheReusesTheSameLanesRebuildsOtherOnes) {
  test::TempDir dir;
  const std::string exemplar = (test::source_dir() / "samples/exemplars/hedge_192x48.png").string();
  const auto run = [&](const std::string& out, const std::string& seed) {
    run_pipeline(demo(dir / out, {{"features.lanes.synthesis.exemplar", exemplar},
                                  {"features.lanes.synthesis.delta", "8"},
                                  {"features.lanes.network.seed", seed},
                                  {"cache", (dir / "cache").string()}}));
    const nlohmann::json report = nlohmann::json::parse(test::read_file(dir / out / "report.json"));
    std::map<std::string, int> statuses;
    for (const auto& f : report["classes"][2]["features"])
      if (f.contains("synthesis")) ++statuses[f["cache"]["status"].get<std::string>()];
    return statuses;
  };
  const auto first = run("a", "7");
  EXPECT_GT(first.at("rebuilt"), 8);
  const auto second = run("b", "7");
  EXPECT_EQ(second.at("reused"), first.at("rebuilt"));
  EXPECT_EQ(second.count("rebuilt"), 0u);
  EXPECT_EQ(test::read_file(dir / "a/splat.tif"), test::read_file(dir / "b/splat.tif"));
  const auto other = run("c", "8");
  EXPECT_GT(other.at("rebuilt"), 8);
}

TEST(NetworkRun, APartialDrawingIsKeptAndCompleted) {
  test::TempDir dir;
  // Two lanes drawn by the user, meeting in a T, inside the region.
  test::write_layer(dir / "drawn.gpkg", "drawn",
                    {{"LINESTRING (291100 9114200, 291300 9114210, 291500 9114200)"},
                     {"LINESTRING (291300 9114210, 291310 9114350)"}},
                    "EPSG:31985");
  Warnings warnings;
  const WorldPlan plan = plan_world(demo(dir / "p", {{"features.lanes.network.partial",
                                                      (dir / "drawn.gpkg").string() + ":drawn"}}),
                                    {}, warnings);
  const auto& lanes = plan.lines.at(2);
  ASSERT_TRUE(detail::network_class_report(plan.report, 2));
  const auto& report = *detail::network_class_report(plan.report, 2);
  EXPECT_EQ(report.method, "automatic");
  EXPECT_EQ(report.chosen, "growth");  // completing a drawing is growth
  // The T splits the first line (3 edges), and lanes grown onto them split them further.
  EXPECT_GE(report.kept, 3);
  EXPECT_GT(int(lanes.size()), report.kept);
  // The drawn vertices come out exactly as drawn, in lines of the class.
  for (const Vec2 p : {Vec2{291100, 9114200}, Vec2{291300, 9114210}, Vec2{291500, 9114200},
                       Vec2{291310, 9114350}}) {
    bool found = false;
    for (const LineFeature& l : lanes)
      found = found || std::find(l.points.begin(), l.points.end(), p) != l.points.end();
    EXPECT_TRUE(found) << p.x << " " << p.y;
  }
}

// One reading of a drawing (network/partial.hpp): a `partial` whose lines cross is refused by
// the run with the command's words, naming the file and the FIDs (not noded into a junction).
TEST(NetworkRun, CrossingPartialIsRefusedAsTheCommandRefusesIt) {
  test::TempDir dir;
  test::write_layer(dir / "drawn.gpkg", "drawn",
                    {{"LINESTRING (291100 9114100, 291300 9114300)"},
                     {"LINESTRING (291100 9114300, 291300 9114100)"}},
                    "EPSG:31985");
  const std::string drawing = (dir / "drawn.gpkg").string() + ":drawn";
  std::string run_error = "no error";
  try {
    Warnings warnings;
    plan_world(demo(dir / "p", {{"features.lanes.network.partial", drawing}}), {}, warnings);
  } catch (const Error& e) {
    run_error = e.what();
  }
  const test::CommandResult command =
      test::run_command(test::terraweave_binary().string() + " network complete --exemplar " +
                        (test::source_dir() / "tests/data/network_drawn.svg").string() +
                        " --scale 0.5 --region 291000,9114000,291600,9114400 --partial " + drawing +
                        " --out " + (dir / "c").string() + " 2>&1");
  EXPECT_EQ(command.exit_code, 1);
  const std::string words =
      drawing + ": FID 1 crosses FID 2 (a partial network may meet itself only where a line ends)";
  EXPECT_THAT(run_error, HasSubstr("features.lanes.network.partial " + words));
  EXPECT_THAT(command.output, HasSubstr("--partial " + words));
}

// A drawing in another CRS (WGS 84) is moved into the heightfield's (UTM 25S), as map layers
// are; one without a CRS is refused, as a map layer without one is.
TEST(NetworkRun, APartialDrawingInAnotherCrsIsReprojected) {
  test::TempDir dir;
  const std::vector<Vec2> drawn = {
      {291100, 9114200}, {291300, 9114210}, {291500, 9114200}, {291310, 9114350}};
  OGRSpatialReference utm, wgs84;
  utm.importFromEPSG(31985);
  wgs84.importFromEPSG(4326);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_wgs84(
      OGRCreateCoordinateTransformation(&utm, &wgs84));
  ASSERT_NE(to_wgs84, nullptr);
  std::vector<std::array<double, 2>> lonlat;
  for (Vec2 p : drawn) {
    double x = p.x, y = p.y;
    ASSERT_TRUE(to_wgs84->Transform(1, &x, &y));
    lonlat.push_back({x, y});
  }
  const std::vector<test::VectorFeature> lines = {
      test::VectorFeature({lonlat[0], lonlat[1], lonlat[2]}, 4.0),
      test::VectorFeature({lonlat[1], lonlat[3]}, 4.0)};
  test::write_layer(dir / "drawn.gpkg", "drawn", lines, "EPSG:4326");
  test::write_layer(dir / "nocrs.shp", "nocrs", lines, "");  // a Shapefile without .prj
  Warnings warnings;
  const WorldPlan plan = plan_world(demo(dir / "p", {{"features.lanes.network.partial",
                                                      (dir / "drawn.gpkg").string() + ":drawn"}}),
                                    {}, warnings);
  const auto& lanes = plan.lines.at(2);
  ASSERT_TRUE(detail::network_class_report(plan.report, 2));
  EXPECT_GE(detail::network_class_report(plan.report, 2)->kept, 3);
  for (const Vec2 p : drawn) {
    double nearest = INFINITY;
    for (const LineFeature& l : lanes)
      for (Vec2 q : l.points) nearest = std::min(nearest, distance(p, q));
    EXPECT_LT(nearest, 1e-3) << p.x << " " << p.y;
  }
  std::string message = "no error";
  try {
    plan_world(demo(dir / "q", {{"features.lanes.network.partial", (dir / "nocrs.shp").string()}}),
               {}, warnings);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_THAT(message, HasSubstr("features.lanes.network.partial"));
  EXPECT_THAT(message, HasSubstr("layer has no CRS"));
}

// The sample DEM with a hole of 2 x 2 nodata cells (180 m a side) in the middle of the lanes'
// region: no lane passes over it (each segment sampled every 0.5 m).
TEST(NetworkRun, LanesStayOffTheHeightfieldsNodata) {
  test::TempDir dir;
  GDALAllRegister();
  const fs::path dem = dir / "holed.tif";
  double transform[6];
  {
    GDALDatasetUniquePtr src(GDALDataset::Open((test::source_dir() / "samples/dem.tif").c_str(),
                                               GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_NE(src, nullptr);
    GDALDatasetUniquePtr copy(GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(
        dem.c_str(), src.get(), FALSE, nullptr, nullptr, nullptr));
    ASSERT_NE(copy, nullptr);
    copy->GetGeoTransform(transform);
    GDALRasterBand* band = copy->GetRasterBand(1);
    ASSERT_EQ(band->SetNoDataValue(-9999.0), CE_None);
    float hole[4] = {-9999.f, -9999.f, -9999.f, -9999.f};
    ASSERT_EQ(band->RasterIO(GF_Write, 15, 50, 2, 2, hole, 2, 2, GDT_Float32, 0, 0), CE_None);
  }
  const auto on_hole = [&](Vec2 p) {
    const double col = (p.x - transform[0]) / transform[1];
    const double row = (p.y - transform[3]) / transform[5];
    return col >= 15 && col < 17 && row >= 50 && row < 52;
  };
  Warnings warnings;
  const WorldPlan plan = plan_world(demo(dir / "p", {{"heightfield", dem.string()}}), {}, warnings);
  const auto& lanes = plan.lines.at(2);
  ASSERT_GE(lanes.size(), 8u);
  int samples = 0;
  for (std::size_t i = 0; i < lanes.size(); ++i)
    for (std::size_t k = 0; k + 1 < lanes[i].points.size(); ++k) {
      const Vec2 a = lanes[i].points[k], b = lanes[i].points[k + 1];
      const int n = 1 + int(distance(a, b) / 0.5);
      for (int s = 0; s <= n; ++s, ++samples) {
        const Vec2 p = a + (b - a) * (double(s) / n);
        ASSERT_FALSE(on_hole(p)) << "lane " << i << " at " << p.x << " " << p.y;
      }
    }
  EXPECT_GT(samples, 1000);
}

// An area class's polygon in the lanes' region: its shape-patterns fill it later, so no lane
// enters it (sampled every 0.5 m, 2 m inside its edge: the mask's cells are a metre); without the
// area class, lanes cross the same square.
TEST(NetworkRun, LanesStayOutOfTheAreaClassesPolygons) {
  test::TempDir dir;
  const double x0 = 291200, y0 = 9114120, x1 = 291380, y1 = 9114300;
  test::write_layer(
      dir / "plots.gpkg", "plots",
      {{fmt::format("POLYGON (({0} {1}, {2} {1}, {2} {3}, {0} {3}, {0} {1}))", x0, y0, x1, y1)}},
      "EPSG:32725");
  std::string yaml = test::read_file(kDemo);
  for (std::size_t at = yaml.find("../"); at != std::string::npos; at = yaml.find("../", at))
    yaml.replace(at, 3, test::source_dir().string() + "/");
  const std::string plots =
      "  plots:\n    kind: area\n    source: " + (dir / "plots.gpkg").string() +
      "\n    layer: plots\n    sketch: " +
      (test::source_dir() / "samples/sketches/orchard.geojson").string() +
      "\n    scale: 40\n    materials: { crown: orchard_crown, trunk: "
      "orchard_trunk }\n";
  const std::string with_plots = std::string(yaml).insert(yaml.find("existing:"), plots);
  const auto lanes_in_square = [&](const std::string& text) {
    std::ofstream(dir / "p.yaml") << text;
    Warnings warnings;
    const WorldPlan plan = plan_world(
        load_pipeline(dir / "p.yaml", {{"output.dir", (dir / "out").string()}}), {}, warnings);
    const auto& lanes = plan.lines.at(2);
    EXPECT_GE(lanes.size(), 8u);
    int inside = 0;
    for (const LineFeature& lane : lanes)
      for (std::size_t k = 0; k + 1 < lane.points.size(); ++k) {
        const Vec2 a = lane.points[k], b = lane.points[k + 1];
        const int n = 1 + int(distance(a, b) / 0.5);
        for (int s = 0; s <= n; ++s) {
          const Vec2 p = a + (b - a) * (double(s) / n);
          inside += p.x > x0 + 2 && p.x < x1 - 2 && p.y > y0 + 2 && p.y < y1 - 2;
        }
      }
    return inside;
  };
  EXPECT_GT(lanes_in_square(yaml), 0) << "the square is where lanes grow without the area";
  EXPECT_EQ(lanes_in_square(with_plots), 0);
}

// `choose: mix` on a network class: near_junction binds the crossing exemplar around the grown
// junctions (a small region: a few lanes); a where or tags rule has no layer to ask and is
// refused naming the rule.
TEST(NetworkRun, MixBindsNearJunctionsAndRefusesAttributeRules) {
  test::TempDir dir;
  const fs::path exemplars = test::source_dir() / "samples/exemplars";
  const std::string list = "[" + (exemplars / "hedge_192x48.png").string() + ", " +
                           (exemplars / "crossing_240x64.png").string() + "]";
  const auto mix = [&](const fs::path& out, const std::string& rule) {
    return demo(out, {{"region", "[290990, 9113990, 291310, 9114210]"},
                      {"features.lanes.network.region", "[291000, 9114000, 291300, 9114200]"},
                      {"features.lanes.synthesis.exemplar", list},
                      {"features.lanes.synthesis.choose", "mix"},
                      {"features.lanes.synthesis.delta", "8"},
                      {"features.lanes.synthesis.bind", "[{exemplar: 1, " + rule + "}]"}});
  };
  run_pipeline(mix(dir / "m", "near_junction: 10"));
  const nlohmann::json report = nlohmann::json::parse(test::read_file(dir / "m/report.json"));
  EXPECT_EQ(report["pattern_violations"].get<int>(), 0);
  const auto& classes = report["classes"];
  const auto lanes = std::find_if(classes.begin(), classes.end(),
                                  [](const auto& c) { return c["name"] == "lanes"; });
  ASSERT_NE(lanes, classes.end());
  std::map<std::string, int> pieces;
  int mixed = 0;
  for (const auto& f : (*lanes)["features"]) {
    if (!f.contains("synthesis") || !f["synthesis"].contains("mix")) continue;
    ++mixed;
    const auto& m = f["synthesis"]["mix"];
    for (std::size_t e = 0; e < m["exemplars"].size(); ++e)
      pieces[fs::path(m["exemplars"][e].get<std::string>()).filename().string()] +=
          m["pieces_per_exemplar"][e].get<int>();
  }
  EXPECT_GE(mixed, 3);
  EXPECT_GT(pieces["hedge_192x48.png"], 0);
  EXPECT_GT(pieces["crossing_240x64.png"], 0);
  for (const std::string rule : {"where: \"1 = 1\"", "tags: {highway: [track]}"}) {
    std::string message = "no error";
    try {
      mix(dir / "w", rule);
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_THAT(message, HasSubstr("features.lanes.synthesis.bind.0")) << rule;
    EXPECT_THAT(message, HasSubstr("bind them by near_junction")) << rule;
  }
}

TEST(NetworkRun, ErrorsNameTheKey) {
  test::TempDir dir;
  std::ofstream(dir / "empty.svg")
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"></svg>\n";
  const auto message = [&](std::vector<Override> overrides) {
    try {
      Warnings warnings;
      plan_world(demo(dir / "x", std::move(overrides)), {}, warnings);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message({{"features.lanes.network.exemplar", (dir / "empty.svg").string()}}),
              HasSubstr("features.lanes.network.exemplar"));
  EXPECT_THAT(message({{"features.lanes.network.exemplar", (dir / "none.gpkg").string()}}),
              HasSubstr("features.lanes.network.exemplar"));
  EXPECT_THAT(message({{"features.lanes.network.region", "[291000, 9114000, 291000, 9114400]"}}),
              HasSubstr("features.lanes.network.region"));
  // A region far too large for fields of 100 m.
  EXPECT_THAT(message({{"features.lanes.network.region", "[0, 0, 9000000, 9000000]"}}),
              HasSubstr("features.lanes.network.region"));
  EXPECT_THAT(message({{"features.lanes.network.candidates", "0"}}),
              HasSubstr("features.lanes.network.candidates"));
  EXPECT_THAT(message({{"features.lanes.network.colour", "red"}}),
              HasSubstr("features.lanes.network.colour"));
  EXPECT_THAT(message({{"features.lanes.network.method", "quilts"}}),
              HasSubstr("features.lanes.network.method: unknown method 'quilts', expected "
                        "automatic, growth, quilt or layout (did you mean 'quilt'?)"));
  // Completing a drawing is growth (docs/networks.md, "Which method"): the quilt and the layout
  // are refused.
  test::write_layer(dir / "drawn.gpkg", "drawn", {{"LINESTRING (291100 9114200, 291300 9114210)"}},
                    "EPSG:31985");
  for (const std::string method : {"quilt", "layout"}) {
    const std::string refused =
        message({{"features.lanes.network.partial", (dir / "drawn.gpkg").string() + ":drawn"},
                 {"features.lanes.network.method", method}});
    EXPECT_THAT(refused, HasSubstr("features.lanes.network.method"));
    EXPECT_THAT(refused, HasSubstr(method + " cannot complete `partial`"));
  }
}

}  // namespace
}  // namespace tw
