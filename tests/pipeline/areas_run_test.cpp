// `kind: area` classes inside a run (docs/shape-patterns.md): shapes kept off the run's roads,
// lead directions from the nearest road and from the terrain's contours, height detail and
// splat materials, the vector and instance outputs with their manifest hashes, determinism, and
// the plan folder's round trip.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "layers/layer_set.hpp"
#include "pipeline/job.hpp"
#include "pipeline/lead_direction.hpp"
#include "pipeline/methods/areas/area_config.hpp"
#include "pipeline/methods/areas/area_method.hpp"
#include "pipeline/methods/areas/area_report.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/run.hpp"
#include "pipeline/synthesis_job.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/sparse_raster.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// 100 x 100 cells of 4 m: x 500000..500400, y 4999600..5000000. A straight road at compass
// bearing 30 degrees crosses the vineyard; the orchard lies beside it without touching it.
constexpr const char* kWorld = R"(
version: 1
seed: 3
generate: { width: 100, height: 100, pixel_size: 4, relief: 30 }
output: { dir: out, preview: false }
synthesis_resolution: 1
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 8 }
  vines:
    kind: area
    source: map.gpkg
    layer: fields
    where: "crop = 'vine'"
    sketch: vineyard.geojson
    scale: 100
    lead: nearest_road
    materials: { vine: vine_row, post: vine_post }
    height: { vine: 0.3 }
  orchard:
    kind: area
    source: map.gpkg
    layer: fields
    where: "crop = 'fruit'"
    sketch: orchard.geojson
    scale: 60
    lead: { bearing: 90 }
)";

// The road from (500050, 4999650) at bearing 30: direction (sin 30, cos 30).
const Vec2 kRoadStart{500050.0, 4999650.0};
const Vec2 kRoadDirection{0.5, std::sqrt(3.0) / 2.0};
constexpr double kRoadWidth = 8.0;

double distance_to_road(Vec2 p) {
  const Vec2 d = p - kRoadStart;
  return std::abs(d.x * kRoadDirection.y - d.y * kRoadDirection.x);
}

class AreaRun : public ::testing::Test {
 protected:
  void SetUp() override {
    const Vec2 end = kRoadStart + kRoadDirection * 400.0;
    test::write_layer(
        dir_ / "map.gpkg", "roads",
        {{fmt::format("LINESTRING ({} {}, {} {})", kRoadStart.x, kRoadStart.y, end.x, end.y)}});
    write_fields();
    for (const char* sketch : {"vineyard.geojson", "orchard.geojson"})
      fs::copy_file(test::source_dir() / "samples/sketches" / sketch, dir_ / sketch);
  }

  // Two polygons with a `crop` column (test_world's writer has only `width`): GDAL directly.
  void write_fields() const {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    std::unique_ptr<GDALDataset> ds(
        GDALDataset::Open((dir_ / "map.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
    ASSERT_TRUE(driver && ds);
    OGRSpatialReference srs;
    srs.importFromEPSG(32631);
    OGRLayer* layer = ds->CreateLayer("fields", &srs, wkbPolygon, nullptr);
    OGRFieldDefn crop("crop", OFTString);
    ASSERT_EQ(layer->CreateField(&crop), OGRERR_NONE);
    for (auto [value, wkt] : {std::pair{"vine",
                                        "POLYGON ((500060 4999700, 500260 4999700, 500260 4999880, "
                                        "500060 4999880, 500060 4999700))"},
                              {"fruit",
                               "POLYGON ((500250 4999620, 500390 4999620, 500390 4999720, "
                               "500250 4999720, 500250 4999620))"}}) {
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetField("crop", value);
      OGRGeometry* geometry = nullptr;
      ASSERT_EQ(OGRGeometryFactory::createFromWkt(wkt, &srs, &geometry), OGRERR_NONE);
      feature.SetGeometryDirectly(geometry);
      ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    }
  }

  PipelineConfig config(const std::string& out, std::vector<Override> overrides = {}) const {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    return parse_pipeline(kWorld, "world.yaml", dir_.path(), overrides);
  }

  test::TempDir dir_;
};

TEST_F(AreaRun, ShapesKeepOffTheRoadAndFollowItsDirection) {
  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  ASSERT_EQ(detail::areas_plan(plan)->areas.size(), 2u);
  const detail::AreaFeatureReport& vines = detail::area_reports(plan.report).at(0).features.at(0);
  EXPECT_NEAR(vines.lead_bearing_deg, 30.0, 1e-6);  // along the road
  EXPECT_GT(vines.shapes, 20);
  EXPECT_GT(vines.forbidden, 0);  // the road crosses the field: candidates on it left out
  EXPECT_EQ(vines.forbidden_touched, 0);
  // Every stroke stays clear of the road's footprint (up to a canvas cell's diagonal, the
  // avoidance lattice's resolution).
  int left = 0, right = 0;
  for (const PlacedStroke& s : detail::areas_plan(plan)->areas[0].pattern.strokes)
    for (const Vec2 p : s.points) {
      EXPECT_GT(distance_to_road(p), 0.5 * (kRoadWidth + s.width) - std::sqrt(2.0));
      const Vec2 d = p - kRoadStart;
      (d.x * kRoadDirection.y - d.y * kRoadDirection.x > 0 ? right : left)++;
    }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
  const detail::AreaFeatureReport& orchard = detail::area_reports(plan.report).at(1).features.at(0);
  EXPECT_NEAR(orchard.lead_bearing_deg, 90.0, 1e-9);
  EXPECT_GT(orchard.shapes, 10);
  EXPECT_EQ(orchard.forbidden_touched, 0);
  EXPECT_EQ(detail::areas_plan(plan)->names, (std::vector<std::string>{"vines", "orchard"}));
  for (const char* m : {"vine_row", "vine_post", "orchard_trunk", "orchard_crown"})
    EXPECT_NE(std::find(plan.splat_materials.begin(), plan.splat_materials.end(), m),
              plan.splat_materials.end())
        << m;
}

// A method before the areas that keeps them out of the vine field's west half (x below
// kKeepWestEdge) through the seam, as the curve patterns keep them off their coverage: a band
// burnt on the areas' canvases by SynthesisMethod::keep_out.
constexpr double kKeepWestEdge = 500160.0;
struct AreaKeepWestPlan : MethodPayloadOf<AreaKeepWestPlan> {};
class AreaKeepWestMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return "keep_west"; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig&, const PlanOptions&) const override { return true; }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<AreaKeepWestPlan>();
  }
  void plan(MethodContext&, MethodPlan&) const override {}
  void keep_out(const MethodPlan&, const GridSpec& lattice,
                SparseRaster<std::uint8_t>& forbidden) const override {
    const std::vector<Vec2> band = {{kKeepWestEdge - 60.0, 4999500.0},
                                    {kKeepWestEdge - 60.0, 5000000.0}};
    burn_buffered_lines_on({&band}, {120.0}, lattice, forbidden, 1);
  }
  nlohmann::json encode(const MethodPlan&, detail::PlanObjects&) const override { return {}; }
  void decode(const nlohmann::json&, detail::PlanObjects&, MethodPlan&) const override {}
};

TEST_F(AreaRun, ShapesKeepOutOfWhatTheMethodsBeforeThemKeepOut) {
  const AreaKeepWestMethod keep_west;
  auto west_points = [](const WorldPlan& plan, double margin) {
    int west = 0;
    for (const PlacedStroke& s : detail::areas_plan(plan)->areas.at(0).pattern.strokes)
      for (const Vec2 p : s.points) west += p.x < kKeepWestEdge + 0.5 * s.width - margin;
    return west;
  };
  Warnings warnings;
  PlanOptions options;
  options.methods = {&detail::area_method()};
  const WorldPlan alone = plan_world(config("alone"), options, warnings);
  EXPECT_GT(west_points(alone, 0.0), 20);  // without it, the vines fill the west half too
  options.methods = {&keep_west, &detail::area_method()};
  const WorldPlan kept = plan_world(config("kept"), options, warnings);
  // Up to a canvas cell's diagonal, the avoidance lattice's resolution.
  EXPECT_EQ(west_points(kept, std::sqrt(2.0)), 0);
  EXPECT_GT(detail::areas_plan(kept)->areas.at(0).pattern.strokes.size(), 5u);
}

TEST_F(AreaRun, RowsRaiseTheTerrainByTheirHeightDetailAndPaintTheirSplat) {
  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  WorldPlan bare = plan;
  detail::areas_plan(bare)->areas.clear();
  index_plan(bare);
  const LayerSet with = render_tile(plan, plan.tiles.at(0));
  const LayerSet without = render_tile(bare, bare.tiles.at(0));
  const auto& h1 = find_layer(with, "height")->bands[0].pixels;
  const auto& h0 = find_layer(without, "height")->bands[0].pixels;
  double max_rise = 0.0;
  for (std::size_t i = 0; i < h1.size(); ++i) {
    EXPECT_GE(h1[i], h0[i] - 1e-4f);
    max_rise = std::max(max_rise, double(h1[i] - h0[i]));
  }
  EXPECT_LE(max_rise, 0.3 + 1e-4);
  EXPECT_GT(max_rise, 0.05);  // 1.2 m rows on 4 m pixels: about 0.3 of a pixel
  const Layer& splat = *find_layer(with, "splat");
  const auto row = std::find(splat.channels.begin(), splat.channels.end(), "splat.vine_row");
  ASSERT_NE(row, splat.channels.end());
  const auto& band = splat.bands[std::size_t(row - splat.channels.begin())].pixels;
  EXPECT_GT(*std::max_element(band.begin(), band.end()), 0.2f);
  for (std::size_t i = 0; i < band.size(); i += 7) {
    float sum = 0.0f;
    for (const Raster<float>& b : splat.bands) sum += b.pixels[i];
    EXPECT_NEAR(sum, 1.0f, 1e-4f);
  }
}

TEST_F(AreaRun, OutputsAreTheSameBytesAtAnyThreadCountAndInTheManifest) {
  RunOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RunReport a = run_pipeline(config("a"), one);
  run_pipeline(config("b"), two);
  for (const char* file : {"areas.gpkg", "instances.csv", "instances.json", "splat.exr"})
    EXPECT_EQ(test::read_file(dir_ / "a" / file), test::read_file(dir_ / "b" / file)) << file;
  const nlohmann::json report = nlohmann::json::parse(test::read_file(dir_ / "a/report.json"));
  std::vector<std::string> named;
  for (const auto& f : report["outputs"]) named.push_back(f["path"]);
  for (const char* file : {"areas.gpkg", "instances.csv", "instances.json"})
    EXPECT_NE(std::find(named.begin(), named.end(), file), named.end()) << file;
  const auto& vines = report["areas"][0];
  EXPECT_EQ(vines["name"], "vines");
  EXPECT_EQ(vines["lead"], "nearest_road");
  EXPECT_EQ(vines["forbidden_touched"], 0);
  EXPECT_GT(vines["features"][0]["left_out"]["forbidden"].get<int>(), 0);
  // One instance per shape placed, in the CSV and the JSON.
  const int shapes = vines["shapes"].get<int>() + report["areas"][1]["shapes"].get<int>();
  const std::string csv = test::read_file(dir_ / "a/instances.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), shapes + 1);
  const nlohmann::json instances =
      nlohmann::json::parse(test::read_file(dir_ / "a/instances.json"));
  ASSERT_EQ(int(instances.size()), shapes);
  EXPECT_EQ(instances[0]["class"], "vines");
  EXPECT_EQ(detail::area_reports(a).at(1).features.at(0).shapes,
            report["areas"][1]["shapes"].get<int>());
}

TEST_F(AreaRun, ARenderFromTheSavedPlanIsTheSameBytes) {
  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  save_plan(plan, dir_ / "plan");
  const WorldPlan loaded = load_plan(dir_ / "plan");
  ASSERT_EQ(detail::areas_plan(loaded)->areas.size(), detail::areas_plan(plan)->areas.size());
  const LayerSet a = render_tile(plan, plan.tiles.at(0));
  const LayerSet b = render_tile(loaded, loaded.tiles.at(0));
  ASSERT_EQ(a.layers.size(), b.layers.size());
  for (std::size_t l = 0; l < a.layers.size(); ++l)
    for (std::size_t c = 0; c < a.layers[l].bands.size(); ++c)
      EXPECT_EQ(a.layers[l].bands[c].pixels, b.layers[l].bands[c].pixels) << a.layers[l].name;
}

// Band 1 of a GeoTIFF, row-major.
std::vector<float> read_band(const fs::path& path, int& width) {
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  if (!ds) return {};
  width = ds->GetRasterXSize();
  std::vector<float> pixels(std::size_t(width) * ds->GetRasterYSize());
  if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, width, ds->GetRasterYSize(), pixels.data(),
                                     width, ds->GetRasterYSize(), GDT_Float32, 0, 0) != CE_None)
    return {};
  return pixels;
}

TEST_F(AreaRun, InstancesStandOnTheFinalHeightNotTheInput) {
  run_pipeline(config("a"), {});
  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  int width = 0;
  const std::vector<float> final_height = read_band(dir_ / "a/height.tif", width);
  ASSERT_EQ(width, plan.grid.width);
  const Raster<float> input = read_height_window(plan.heights, plan.grid, Window::whole(plan.grid));
  const nlohmann::json instances =
      nlohmann::json::parse(test::read_file(dir_ / "a/instances.json"));
  ASSERT_GT(instances.size(), 30u);
  int raised = 0;
  for (const auto& instance : instances) {
    const Vec2 p =
        plan.grid.world_to_pixel({instance["x"].get<double>(), instance["y"].get<double>()});
    const int col = int(std::floor(p.x)), row = int(std::floor(p.y));
    ASSERT_TRUE(instance["z"].is_number()) << instance.dump();
    const double z = instance["z"].get<double>();
    EXPECT_NEAR(z, final_height[std::size_t(row * width + col)], 5e-4) << instance.dump();
    raised += std::abs(z - input.at(col, row)) > 0.02;  // the vine rows' +0.3 m, the road's grade
  }
  EXPECT_GT(raised, 10);
  // The CSV and the GeoPackage say the same.
  const std::string csv = test::read_file(dir_ / "a/instances.csv");
  const std::size_t second_line = csv.find('\n') + 1;
  const std::string first = csv.substr(second_line, csv.find('\n', second_line) - second_line);
  EXPECT_THAT(first, HasSubstr(fmt::format(",{:.3f},", instances[0]["z"].get<double>())));
  std::unique_ptr<GDALDataset> gpkg(
      GDALDataset::Open((dir_ / "a/areas.gpkg").c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(gpkg);
  OGRLayer* layer = gpkg->GetLayerByName("instances");
  ASSERT_NE(layer, nullptr);
  std::unique_ptr<OGRFeature> feature(layer->GetNextFeature());
  ASSERT_TRUE(feature);
  const OGRPoint* point = feature->GetGeometryRef()->toPoint();
  EXPECT_NEAR(point->getZ(), instances[0]["z"].get<double>(), 5e-4);
}

// The world tiled, its roads with a cobble pattern the areas avoid: the areas need every curve
// synthesis first, so `plan --synthesis tasks` leaves them to complete-plan.
std::string distributed_world(const std::string& out) {
  std::string text = kWorld;
  text.replace(text.find("output: { dir: out, preview: false }"),
               std::strlen("output: { dir: out, preview: false }"),
               "output: { dir: " + out + ", preview: false, tiles: { size: 40, overlap: 4 } }");
  const std::string road = "kind: road, width: 8";
  text.replace(text.find(road), road.size(),
               road +
                   ", synthesis: { exemplar: cobble.png, width: 8, scale: 5, delta: 8, channels: "
                   "{ alpha: splat.cobble } }");
  return text;
}

TEST_F(AreaRun, SynthesisAsTasksGivesTheAreasOfAnInlineRunBitForBit) {
  test::crop_raster(test::source_dir() / "samples/exemplars/cobble_edging_200x56.png",
                    dir_ / "cobble.png", "PNG", 60, 56);
  const fs::path file = dir_ / "distributed.yaml";
  write_file_atomic(file, distributed_world((dir_ / "local").string()));
  const PipelineConfig config = load_pipeline(file, {});
  const RunReport local = run_pipeline(config, {});
  ASSERT_EQ(detail::area_reports(local).size(), 2u);

  PlanJobOptions options;
  options.output_dir = dir_ / "inline";
  const std::string inline_plan = plan_job(config, options).plan;
  options.output_dir = dir_ / "tasks";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config, options);
  ASSERT_GE(job.syntheses, 1u);
  EXPECT_TRUE(
      detail::areas_plan(load_plan(job.plan_dir))->areas.empty());  // not before the curve patterns
  for (std::size_t i = 0; i < job.syntheses; ++i) synthesize_job_feature(job.plan_dir, int(i));
  const PlannedJob complete = complete_job_plan(job.plan_dir);
  EXPECT_EQ(complete.plan, inline_plan);  // the same plan: the same areas, the same tiles
  const WorldPlan plan = load_plan(job.plan_dir);
  ASSERT_EQ(detail::areas_plan(plan)->areas.size(), 2u);
  EXPECT_FALSE(detail::patterns_plan(plan)->patterns.empty());
  EXPECT_EQ(detail::area_reports(plan.report).at(0).features.at(0).forbidden_touched, 0);
  for (std::size_t t = 0; t < complete.tiles; ++t) render_job_tile(job.plan_dir, int(t));
  finish_job(job.plan_dir);

  std::vector<fs::path> compared = {"areas.gpkg", "instances.csv", "instances.json"};
  for (const auto& entry : fs::directory_iterator(dir_ / "local/tiles"))
    compared.push_back(fs::path("tiles") / entry.path().filename());
  EXPECT_GE(compared.size(), 3u + 9u);
  for (const fs::path& name : compared)
    EXPECT_EQ(test::read_file(dir_ / "local" / name), test::read_file(dir_ / "tasks" / name))
        << name;
  const nlohmann::json a = nlohmann::json::parse(test::read_file(dir_ / "local/report.json"));
  const nlohmann::json b = nlohmann::json::parse(test::read_file(dir_ / "tasks/report.json"));
  EXPECT_EQ(a["areas"], b["areas"]);
  // Every instance has its z from a tile (the tiles' facts, through the workers' results).
  for (const auto& instance : nlohmann::json::parse(test::read_file(dir_ / "tasks/instances.json")))
    EXPECT_TRUE(instance["z"].is_number()) << instance.dump();
  EXPECT_GT(a["areas"][0]["shapes"].get<int>(), 20);
}

// A polygon far too large for its scale is refused before anything is allocated: one error
// naming the class, the FID and the numbers (not a bare std::bad_alloc).
TEST_F(AreaRun, APolygonTooLargeForItsScaleIsRefusedWithItsEstimate) {
  Warnings warnings;
  try {
    plan_world(config("p", {{"features.vines.scale", "0.01"}}), {}, warnings);
    ADD_FAILURE() << "a 36 000 m² polygon at 1 cm per sketch unit was synthesized";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message, HasSubstr("features.vines: FID 1: the polygon (0.036 km²) at scale 0.01 m "
                                   "on 1 m cells would need about "));
    EXPECT_THAT(message, HasSubstr(" shapes, "));
    EXPECT_THAT(message, HasSubstr("GiB allowed (3/4 of this machine's memory)"));
    EXPECT_THAT(message, HasSubstr("split the polygon"));
  }
}

// The vine rows (1.2 m) and posts (0.4 m) are narrower than the 4 m pixels: each warns with the
// splat weight it can reach.
TEST_F(AreaRun, StrokesNarrowerThanAPixelWarnWithTheWeightTheyReach) {
  Warnings warnings;
  plan_world(config("p"), {}, warnings);
  std::vector<std::string> messages;
  for (const Warning& w : warnings.list())
    if (w.code == "area_stroke_subpixel" && w.subject == "features.vines")
      messages.push_back(w.message);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_THAT(messages[0], HasSubstr("strokes of 'post' are 0.4 m wide on 4 m pixels: their splat "
                                     "weight reaches at most 0.10"));
  EXPECT_THAT(messages[1], HasSubstr("strokes of 'vine' are 1.2 m wide on 4 m pixels: their splat "
                                     "weight reaches at most 0.30"));
  // At 1 m pixels the rows are wide enough; the posts still warn.
  Warnings fine;
  plan_world(
      config("q", {{"resolution", "1"}, {"generate.width", "400"}, {"generate.height", "400"}}), {},
      fine);
  int subpixel = 0;
  for (const Warning& w : fine.list())
    if (w.code == "area_stroke_subpixel" && w.subject == "features.vines") {
      ++subpixel;
      EXPECT_THAT(w.message, HasSubstr("strokes of 'post' are 0.4 m wide on 1 m pixels"));
    }
  EXPECT_EQ(subpixel, 1);
}

// Memory follows the polygon, not its box: a 20 m wide strip along the diagonal of a 1.6 km
// world (its box 50 times its area) allocates canvas cells for a band about it.
TEST(AreaCanvas, AThinDiagonalPolygonAllocatesCellsForItsAreaNotItsBox) {
  test::TempDir dir;
  const Vec2 a{500100.0, 4998500.0}, b{501500.0, 4999900.0};
  const Vec2 n = perp(normalized(b - a)) * 10.0;
  test::write_layer(dir / "map.gpkg", "fields",
                    {{fmt::format("POLYGON (({} {}, {} {}, {} {}, {} {}, {} {}))", (a - n).x,
                                  (a - n).y, (b - n).x, (b - n).y, (b + n).x, (b + n).y, (a + n).x,
                                  (a + n).y, (a - n).x, (a - n).y)}});
  fs::copy_file(test::source_dir() / "samples/sketches/orchard.geojson", dir / "orchard.geojson");
  const PipelineConfig config = parse_pipeline(R"(
version: 1
generate: { width: 400, height: 400, pixel_size: 4, relief: 30 }
synthesis_resolution: 1
features:
  strip: { kind: area, source: map.gpkg, layer: fields, sketch: orchard.geojson, scale: 30 }
)",
                                               "strip.yaml", dir.path());
  Warnings warnings;
  const WorldPlan plan = plan_world(config, {}, warnings);
  const detail::AreaFeatureReport& strip = detail::area_reports(plan.report).at(0).features.at(0);
  const double area = strip.area_m2;  // 1 m cells: cells and square metres alike
  EXPECT_NEAR(area, 2.0 * 10.0 * distance(a, b), 1.0);
  const double box = (b.x - a.x + 2.0 * std::abs(n.x)) * (b.y - a.y + 2.0 * std::abs(n.y));
  EXPECT_GT(box, 45.0 * area);
  EXPECT_GT(double(strip.canvas_cells), area);
  EXPECT_LT(double(strip.canvas_cells), 10.0 * area);
  EXPECT_GT(strip.shapes, 50);
  EXPECT_EQ(strip.forbidden_touched, 0);
}

// A canton of Luxembourg over the 30" DEM (nodata -32768 beyond the border): shapes whose
// instance would stand on nodata are left out with a warning; every instance written has a z.
TEST(AreaNodata, InstancesOnNodataAreLeftOutAndEveryInstanceHasItsZ) {
  test::TempDir dir;
  const fs::path samples = test::source_dir() / "samples";
  const std::string pipeline =
      fmt::format(R"(
version: 1
heightfield: {0}/dem_wgs84.tif
resolution: 100
synthesis_resolution: 20
output: {{ dir: {1}, preview: false, exr: false }}
features:
  rocks:
    kind: area
    source: {2}
    sketch: {0}/sketches/boulders.geojson
    scale: 400
)",
                  samples.string(), (dir / "out").string(),
                  (test::source_dir() / "tests/data/lux_remich_2169.geojson").string());
  const RunReport report = run_pipeline(parse_pipeline(pipeline, "remich.yaml", dir.path()), {});
  const detail::AreaFeatureReport& canton = detail::area_reports(report).at(0).features.at(0);
  EXPECT_GT(canton.on_nodata, 0);
  EXPECT_GT(canton.shapes, 100);
  bool warned = false;
  for (const Warning& w : report.warnings)
    warned |= w.code == "area_on_nodata" && w.subject == "features.rocks" && w.fid == canton.fid;
  EXPECT_TRUE(warned);
  const nlohmann::json instances =
      nlohmann::json::parse(test::read_file(dir / "out/instances.json"));
  ASSERT_EQ(int(instances.size()), canton.shapes);
  for (const auto& instance : instances) ASSERT_TRUE(instance["z"].is_number()) << instance.dump();
}

// A plane rising eastward: contours run north-south.
TEST(AreaContours, RowsRunAlongTheContours) {
  test::TempDir dir;
  test::write_dem(dir / "plane.tif", {.width = 50,
                                      .height = 50,
                                      .origin_y = 5000500.0,
                                      .surface = test::DemSpec::Surface::plane_east});
  test::write_layer(dir / "map.gpkg", "fields",
                    {{"POLYGON ((500100 5000100, 500400 5000100, 500400 5000200, 500100 5000200, "
                      "500100 5000100))"}});
  test::write_layer(dir / "map.gpkg", "roads", {{"LINESTRING (500010 5000010, 500490 5000020)"}});
  fs::copy_file(test::source_dir() / "samples/sketches/furrows.geojson", dir / "furrows.geojson");
  const PipelineConfig config = parse_pipeline(R"(
version: 1
heightfield: plane.tif
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
  furrows: { kind: area, source: map.gpkg, layer: fields, sketch: furrows.geojson, lead: contours }
)",
                                               "c.yaml", dir.path());
  Warnings warnings;
  const WorldPlan plan = plan_world(config, {}, warnings);
  const double bearing = detail::area_reports(plan.report).at(0).features.at(0).lead_bearing_deg;
  // The long axis (east-west, 90 degrees) and the road would say otherwise.
  EXPECT_LT(std::min(std::abs(bearing), std::abs(bearing - 180.0)), 0.5) << bearing;
  ASSERT_FALSE(detail::areas_plan(plan)->areas.at(0).pattern.strokes.empty());
  for (const PlacedStroke& s : detail::areas_plan(plan)->areas[0].pattern.strokes) {
    const Vec2 d = s.points.back() - s.points.front();
    EXPECT_LT(std::abs(d.x), 0.1 * std::abs(d.y) + 1e-6);  // furrows run north-south
  }
}

TEST_F(AreaRun, TagsSelectThePolygonsAsTheirWhereClause) {
  Warnings warnings;
  const WorldPlan by_where = plan_world(config("p"), {}, warnings);
  const WorldPlan by_tags = plan_world(config("q", {{"features.vines.where", "\"\""},
                                                    {"features.vines.tags", "{ crop: [vine] }"},
                                                    {"features.orchard.where", "\"\""},
                                                    {"features.orchard.tags", "{ crop: fruit }"}}),
                                       {}, warnings);
  ASSERT_EQ(detail::areas_plan(by_tags)->areas.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(detail::areas_plan(by_tags)->areas[i].fid,
              detail::areas_plan(by_where)->areas[i].fid);
    EXPECT_EQ(detail::areas_plan(by_tags)->areas[i].pattern.instances.size(),
              detail::areas_plan(by_where)->areas[i].pattern.instances.size());
  }
  const WorldPlan none =
      plan_world(config("r", {{"features.vines.tags", "{ crop: [rice] }"}}), {}, warnings);
  EXPECT_EQ(detail::areas_plan(none)->areas.size(), 1u);  // the orchard only
  bool empty_warned = false;
  for (const Warning& w : warnings.list())
    empty_warned |= w.code == "empty_class" && w.subject == "features.vines";
  EXPECT_TRUE(empty_warned);
}

// OSM land use as it comes: samples/olinda.osm's landuse=forest multipolygon, over its DEM.
TEST(AreaTags, AnOsmLanduseSelectsItsPolygon) {
  test::TempDir dir;
  const fs::path samples = test::source_dir() / "samples";
  const std::string pipeline = fmt::format(R"(
version: 1
heightfield: {0}/dem.tif
resolution: 10
features:
  forest:
    kind: area
    source: {0}/olinda.osm
    layer: multipolygons
    tags: {{ landuse: [forest, orchard] }}
    sketch: {0}/sketches/boulders.geojson
    scale: 60
)",
                                           samples.string());
  Warnings warnings;
  const WorldPlan plan =
      plan_world(parse_pipeline(pipeline, "osm_areas.yaml", dir.path()), {}, warnings);
  ASSERT_EQ(detail::areas_plan(plan)->areas.size(), 1u);
  EXPECT_GT(detail::areas_plan(plan)->areas[0].pattern.instances.size(), 5u);
  EXPECT_EQ(detail::area_reports(plan.report).at(0).features.at(0).forbidden_touched, 0);
  Warnings none_warnings;
  const WorldPlan none =
      plan_world(parse_pipeline(pipeline, "osm_areas.yaml", dir.path(),
                                {{"features.forest.tags", "{ landuse: vineyard }"}}),
                 {}, none_warnings);
  EXPECT_TRUE(detail::areas_plan(none)->areas.empty());
}

// terraweave validate analyses the sketches it would synthesize from.
TEST_F(AreaRun, ValidateNamesTheSketchAndTheStrokeOfABrokenSketch) {
  const std::string bad = R"({"type": "FeatureCollection", "features": [
{"type": "Feature", "id": 0, "properties": {"type": "unbounded", "material": "vine"},
 "geometry": {"type": "LineString", "coordinates": [[0, 0.5], [1, 0.5]]}},
{"type": "Feature", "id": 7, "properties": {"material": "post"},
 "geometry": {"type": "LineString", "coordinates": [[0.5, 0.4], [1.5, 0.6]]}}]})";
  write_file_atomic(dir_ / "broken.geojson", bad);
  RunOptions validate;
  validate.write_outputs = false;
  EXPECT_NO_THROW(run_pipeline(config("v"), validate));
  try {
    run_pipeline(config("v", {{"features.orchard.sketch", (dir_ / "broken.geojson").string()}}),
                 validate);
    ADD_FAILURE() << "a broken sketch validated";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("features.orchard: "));
    EXPECT_THAT(e.what(),
                HasSubstr("broken.geojson: stroke 1 (FID 7): point (1.5, 0.6) lies outside"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "v"));  // validate writes nothing
  // A material the class maps but the sketch lacks: a warning, as a run gives it.
  const RunReport report = run_pipeline(
      config("v", {{"features.orchard.materials", "{ leaf: orchard_leaf }"}}), validate);
  bool unused = false;
  for (const Warning& w : report.warnings) unused |= w.code == "area_material_unused";
  EXPECT_TRUE(unused);
}

TEST(AreaConfig, BadKeysAreOneLineNamingTheKey) {
  const auto message = [](const std::string& area) {
    try {
      parse_pipeline(
          "version: 1\nfeatures:\n  vines: { kind: area, source: f.gpkg, sketch: "
          "s.geojson, " +
              area + " }\n",
          "t.yaml", ".");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("lead: nearest_raod"),
              HasSubstr("features.vines.lead: unknown lead 'nearest_raod', expected long_axis, "
                        "nearest_road, contours or { bearing: DEG } (did you mean "
                        "'nearest_road'?)"));
  EXPECT_THAT(message("jitter: 2"), HasSubstr("features.vines.jitter: must be in [0, 1]"));
  EXPECT_THAT(message("lead: { bearing: x }"), HasSubstr("features.vines.lead.bearing"));
  EXPECT_THAT(message("height: { vine: 500 }"), HasSubstr("features.vines.height.vine"));
  EXPECT_THAT(message("width: 3"), HasSubstr("features.vines.width: unknown key"));
  const PipelineConfig c = parse_pipeline(
      "version: 1\nfeatures:\n  vines: { kind: area, source: f.gpkg, sketch: s.geojson, "
      "materials: { vine: row }, height: { vine: 0.3, post: -0.1 } }\n",
      "t.yaml", ".");
  const std::vector<AreaClassConfig>& areas = detail::area_classes(c);
  ASSERT_EQ(areas.size(), 1u);
  EXPECT_TRUE(c.features.empty());
  ASSERT_EQ(areas[0].materials.size(), 2u);
  EXPECT_EQ(areas[0].materials[0].splat, "row");
  EXPECT_DOUBLE_EQ(areas[0].materials[0].height, 0.3);
  EXPECT_EQ(areas[0].materials[1].stroke, "post");
  EXPECT_DOUBLE_EQ(areas[0].materials[1].height, -0.1);
  EXPECT_EQ(areas[0].lead, Lead::long_axis);
}

TEST(AreaCompass, BearingsAreClockwiseFromNorthInZeroTo360) {
  const double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(compass_degrees(pi / 2.0), 0.0);  // +y: north
  EXPECT_DOUBLE_EQ(compass_degrees(0.0), 90.0);      // +x: east
  EXPECT_DOUBLE_EQ(compass_degrees(pi), 270.0);
  // Just past north counter-clockwise: fmod leaves a tiny negative whose + 360 rounds to 360.
  const double just_past = compass_degrees(std::nextafter(pi / 2.0, 4.0));
  EXPECT_GE(just_past, 0.0);
  EXPECT_LT(just_past, 360.0);
  for (double deg : {0.0, 30.0, 90.0, 181.5, 359.0})
    EXPECT_NEAR(compass_degrees(angle_from_compass(deg)), deg, 1e-9);
}

}  // namespace
}  // namespace tw
