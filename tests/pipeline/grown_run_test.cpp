// Grown classes inside a run (docs/pipeline.md, "Grown classes"): hedges, terrace walls and
// ditches grown over their regions (FloralSurf, docs/ornaments.md) become line features: they
// keep off the run's road and each other, change the terrain in their profile's direction, are
// written to ornaments.gpkg (named in report.json with its hash), are the same bytes for the
// same seed and travel in a saved plan; their config errors name the key.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <tuple>

#include "core/error.hpp"
#include "geo/resample.hpp"
#include "layers/layer_set.hpp"
#include "pipeline/methods/grown/grown_classes.hpp"
#include "pipeline/methods/grown/grown_method.hpp"
#include "pipeline/methods/grown/grown_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// 150 x 150 cells of 2 m: x 500000..500300, y 4999700..5000000. A road runs north-south
// through x = 500150; hedges fill the south strip (both sides of the road), ditches the north
// strip, both up to x = 500220, and walls the east half after them (so they must keep off
// them too).
constexpr const char* kWorld = R"(
version: 1
seed: 3
generate: { width: 150, height: 150, pixel_size: 2, relief: 30 }
output: { dir: out, preview: false }
precedence: [roads, hedges, ditches, walls]
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
  hedges:
    kind: hedge
    grow: { element: hedge.json, region: [500010, 4999710, 500220, 4999850], seed: 5 }
  ditches:
    kind: ditch
    grow: { element: ditch.json, region: [500010, 4999860, 500220, 4999990], max_ornaments: 6 }
  walls:
    kind: wall
    grow:
      element: wall.json
      region: { source: map.gpkg, layer: terraces }
      alignment: contour
      max_ornaments: 8
)";

constexpr double kRoadX = 500150.0, kRoadWidth = 6.0;

int orient(Vec2 a, Vec2 b, Vec2 c) {
  const long double v =
      (long double)(b.x - a.x) * (c.y - a.y) - (long double)(b.y - a.y) * (c.x - a.x);
  return (v > 0) - (v < 0);
}
bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (a == c || a == d || b == c || b == d) return false;  // meeting end to end at a joint
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  return o1 * o2 <= 0 && o3 * o4 <= 0 && !(o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0);
}

struct ReadLine {
  std::int64_t fid = 0;
  int ornament = 0;
  std::string name, material, kind;
  double height_m = 0.0;
  std::vector<Vec2> points;
  std::vector<double> z;
};

// Every layer of an ornaments.gpkg, read back with OGR.
std::map<std::string, std::vector<ReadLine>> read_ornaments(const fs::path& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
  std::map<std::string, std::vector<ReadLine>> out;
  if (!ds) return out;
  for (OGRLayer* layer : ds->GetLayers()) {
    auto& lines = out[layer->GetName()];
    for (const auto& feature : *layer) {
      ReadLine& l = lines.emplace_back();
      l.fid = feature->GetFID();
      l.ornament = feature->GetFieldAsInteger("ornament");
      l.name = feature->GetFieldAsString("name");
      l.material = feature->GetFieldAsString("material");
      l.kind = feature->GetFieldAsString("kind");
      l.height_m = feature->GetFieldAsDouble("height_m");
      const auto* g = feature->GetGeometryRef()->toLineString();
      for (int i = 0; i < g->getNumPoints(); ++i) {
        l.points.push_back({g->getX(i), g->getY(i)});
        l.z.push_back(g->getZ(i));
      }
    }
  }
  return out;
}

class GrownRun : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{fmt::format("LINESTRING ({} 4999700, {} 5000000)", kRoadX, kRoadX)}});
    test::write_layer(dir_ / "map.gpkg", "terraces",
                      {{"POLYGON ((500160 4999710, 500290 4999710, 500290 4999990, "
                        "500160 4999990, 500160 4999710))"}});
    for (const char* name : {"hedge.json", "ditch.json", "wall.json"})
      fs::copy_file(test::source_dir() / "samples/ornaments" / name, dir_ / name);
  }

  PipelineConfig config(const std::string& out, std::vector<Override> overrides = {}) const {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    return parse_pipeline(kWorld, "world.yaml", dir_.path(), overrides);
  }

  test::TempDir dir_;
};

TEST_F(GrownRun, LinesInOrnamentsGpkgKeepOffTheRoadAndEachOther) {
  const RunReport report = run_pipeline(config("a"));
  const auto layers = read_ornaments(dir_ / "a/ornaments.gpkg");
  ASSERT_EQ(layers.size(), 3u);
  const std::map<std::string, std::string> kind_of_layer = {
      {"hedges", "hedge"}, {"ditches", "ditch"}, {"walls", "wall"}};
  std::vector<const ReadLine*> all;
  for (const auto& [name, lines] : layers) {
    const auto c = std::find_if(report.classes.begin(), report.classes.end(),
                                [&](const FeatureClassReport& r) { return r.name == name; });
    ASSERT_NE(c, report.classes.end()) << name;
    const detail::GrowthReport* grow =
        detail::growth_report(report, std::size_t(c - report.classes.begin()));
    ASSERT_TRUE(grow) << name;
    EXPECT_EQ(int(lines.size()), grow->lines) << name;
    EXPECT_GE(grow->elements, 3) << name;
    EXPECT_GT(grow->coverage, 0.1) << name;
    // The class's features are the grown lines, FID for FID.
    ASSERT_EQ(c->features.size(), lines.size()) << name;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      EXPECT_EQ(lines[i].fid, std::int64_t(i + 1));
      EXPECT_EQ(c->features[i].fid, lines[i].fid);
      EXPECT_EQ(lines[i].kind, kind_of_layer.at(name));
      all.push_back(&lines[i]);
    }
  }
  EXPECT_DOUBLE_EQ(layers.at("hedges").front().height_m, 1.5);    // the hedge bank's default
  EXPECT_DOUBLE_EQ(layers.at("ditches").front().height_m, -1.0);  // a ditch a metre deep
  // No line crosses another, in a class or across classes (the walls were grown after the
  // hedges, over the same ground).
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j)
      for (std::size_t a = 0; a + 1 < all[i]->points.size(); ++a)
        for (std::size_t b = 0; b + 1 < all[j]->points.size(); ++b)
          ASSERT_FALSE(segments_cross(all[i]->points[a], all[i]->points[a + 1], all[j]->points[b],
                                      all[j]->points[b + 1]))
              << all[i]->kind << " " << all[i]->fid << " x " << all[j]->kind << " " << all[j]->fid;
  // None enters the road's footprint widened by its own half width (the forbidden pixels, by
  // the pixel-centre rule on the 2 m mesh: up to half a pixel diagonal closer).
  int west = 0, east = 0;
  for (const ReadLine& l : layers.at("hedges"))
    for (Vec2 p : l.points) {
      EXPECT_GT(std::abs(p.x - kRoadX), 0.5 * (kRoadWidth + 2.0) - std::sqrt(2.0)) << l.fid;
      (p.x < kRoadX ? west : east)++;
    }
  EXPECT_GT(west, 0);
  EXPECT_GT(east, 0);
  // ornaments.gpkg is in the manifest with its hash, and report.json has the class's growth.
  const nlohmann::json json = nlohmann::json::parse(test::read_file(dir_ / "a/report.json"));
  const auto output = std::find_if(json["outputs"].begin(), json["outputs"].end(),
                                   [](const auto& f) { return f["path"] == "ornaments.gpkg"; });
  ASSERT_NE(output, json["outputs"].end());
  EXPECT_EQ((*output)["xxh3_128"].get<std::string>().size(), 32u);
  const auto& hedges = json["classes"][1];
  EXPECT_EQ(hedges["name"], "hedges");
  EXPECT_EQ(hedges["kind"], "ridge");
  EXPECT_EQ(hedges["grown_kind"], "hedge");
  EXPECT_EQ(hedges["grow"]["lines"].get<int>(), int(layers.at("hedges").size()));
  EXPECT_GT(hedges["grow"]["rejected"]["forbidden"].get<int>(), 0);  // the road and the edge
  EXPECT_GT(hedges["grow"]["coverage"].get<double>(), 0.2);
}

TEST_F(GrownRun, HedgesAndWallsRaiseTheTerrainDitchesLowerIt) {
  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  ASSERT_EQ(detail::grown_plan(plan)->classes.size(), 3u);
  const TileSpec& tile = plan.tiles.at(0);
  const GridSpec grid = window_grid(plan.grid, tile.halo_window);
  const Raster<float> before = read_height_window(plan.heights, plan.grid, tile.halo_window);
  const LayerSet layers = render_tile(plan, tile);
  const Raster<float>& after = find_layer(layers, "height")->bands[0];
  for (const detail::GrownClass& g : detail::grown_plan(plan)->classes) {
    // The change at every line's vertices, averaged: hedge banks and walls stand proud of
    // the ground by about their height, ditches are cut about their depth into it.
    double sum = 0.0;
    int count = 0, wrong_way = 0;
    for (const LineFeature& line : plan.lines[g.class_index])
      for (Vec2 p : line.points) {
        const double d =
            sample_height_bilinear(after, grid, p) - sample_height_bilinear(before, grid, p);
        sum += d;
        ++count;
        wrong_way += g.height_m > 0 ? d < -0.05 : d > 0.05;
      }
    ASSERT_GT(count, 0) << g.kind;
    const double mean = sum / count;
    std::printf("%s: mean change %.3f m at %d vertices (profile %.2f m), %d the wrong way\n",
                g.kind.c_str(), mean, count, g.height_m, wrong_way);
    if (g.height_m > 0) {
      EXPECT_GT(mean, 0.5 * g.height_m) << g.kind;
      EXPECT_LT(mean, 1.2 * g.height_m) << g.kind;
    } else {
      EXPECT_LT(mean, 0.5 * g.height_m) << g.kind;
    }
    EXPECT_LT(wrong_way, count / 50 + 1) << g.kind;
  }
}

TEST_F(GrownRun, SameSeedSameBytesOtherSeedOtherLinesAndThePlanKeepsThem) {
  run_pipeline(config("a"));
  run_pipeline(config("b"));
  EXPECT_EQ(test::read_file(dir_ / "a/ornaments.gpkg"), test::read_file(dir_ / "b/ornaments.gpkg"));
  EXPECT_EQ(test::read_file(dir_ / "a/height.tif"), test::read_file(dir_ / "b/height.tif"));
  run_pipeline(config("c", {{"features.hedges.grow.seed", "9"}}));
  const auto a = read_ornaments(dir_ / "a/ornaments.gpkg");
  const auto c = read_ornaments(dir_ / "c/ornaments.gpkg");
  EXPECT_NE(a.at("hedges").front().points, c.at("hedges").front().points);
  EXPECT_EQ(a.at("ditches").front().points, c.at("ditches").front().points);  // its own seed

  Warnings warnings;
  const WorldPlan plan = plan_world(config("p"), {}, warnings);
  save_plan(plan, dir_ / "plan");
  const WorldPlan loaded = load_plan(dir_ / "plan");
  ASSERT_EQ(detail::grown_plan(loaded)->classes.size(), detail::grown_plan(plan)->classes.size());
  for (std::size_t i = 0; i < detail::grown_plan(plan)->classes.size(); ++i) {
    ASSERT_EQ(detail::grown_plan(loaded)->classes[i].lines.size(),
              detail::grown_plan(plan)->classes[i].lines.size());
    EXPECT_EQ(detail::grown_plan(loaded)->classes[i].lines.back().points,
              detail::grown_plan(plan)->classes[i].lines.back().points);
    EXPECT_EQ(detail::grown_plan(loaded)->classes[i].lines.back().name,
              detail::grown_plan(plan)->classes[i].lines.back().name);
  }
  ASSERT_TRUE(detail::growth_report(loaded.report, 1));
  EXPECT_EQ(detail::growth_report(loaded.report, 1)->elements,
            detail::growth_report(plan.report, 1)->elements);
}

TEST(GrownConfig, DefaultsByKindAndErrorsNameTheKey) {
  const auto parse = [](const std::string& cls) {
    return parse_pipeline("version: 1\nfeatures:\n  h: " + cls + "\n", "t.yaml", "/data");
  };
  const auto message = [&](const std::string& cls) {
    try {
      parse(cls);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const PipelineConfig hedge =
      parse("{ kind: hedge, grow: { element: e.json, region: [0, 0, 9, 9] } }");
  ASSERT_EQ(hedge.features.size(), 1u);
  const FeatureClassConfig& h = hedge.features[0];
  ASSERT_TRUE(has_method_options(h, kGrownMethodName));
  EXPECT_EQ(h.kind, FeatureKind::ridge);
  EXPECT_EQ(method_options<GrowConfig>(h, kGrownMethodName)->kind, "hedge");
  EXPECT_DOUBLE_EQ(h.width, 2.0);
  EXPECT_DOUBLE_EQ(h.ridge.height, 1.5);
  EXPECT_EQ(method_options<GrowConfig>(h, kGrownMethodName)->element, fs::path("/data/e.json"));
  EXPECT_TRUE(h.source.empty());  // the region is given: no source needed
  const FeatureClassConfig d =
      parse(
          "{ kind: ditch, source: r.gpkg, width: 3, profile: { depth: 2 }, grow: { element: "
          "e.json, alignment: contour, trials: 4, clearance: 2 } }")
          .features[0];
  EXPECT_EQ(d.kind, FeatureKind::river);
  EXPECT_DOUBLE_EQ(d.width, 3.0);
  EXPECT_DOUBLE_EQ(d.river.depth, 2.0);
  EXPECT_DOUBLE_EQ(d.river.bank_width, 0.5);  // the ditch's default, not the river's
  EXPECT_TRUE(method_options<GrowConfig>(d, kGrownMethodName)->settings.contour);
  EXPECT_EQ(method_options<GrowConfig>(d, kGrownMethodName)->settings.trials, 4);
  EXPECT_EQ(method_options<GrowConfig>(d, kGrownMethodName)->settings.clearance, 2.0);
  EXPECT_EQ(parse("{ kind: trail, source: r.gpkg, grow: { element: e.json } }").features[0].kind,
            FeatureKind::road);

  EXPECT_THAT(message("{ kind: hedge, source: r.gpkg }"),
              HasSubstr("features.h.kind: a hedge class grows its lines: give a grow: block"));
  EXPECT_THAT(message("{ kind: hedge, source: r.gpkg, grow: { element: e.json, alignment: "
                      "contur } }"),
              HasSubstr("features.h.grow.alignment: unknown alignment 'contur', expected growth "
                        "or contour (did you mean 'contour'?)"));
  EXPECT_THAT(message("{ kind: wall, source: r.gpkg, grow: { element: e.json, trials: 0 } }"),
              HasSubstr("features.h.grow.trials: must be in [1, 1000], got 0"));
  EXPECT_THAT(message("{ kind: wall, grow: { element: e.json, region: [0, 0, 1] } }"),
              HasSubstr("features.h.grow.region: expected [minx, miny, maxx, maxy]"));
  EXPECT_THAT(message("{ kind: wall, grow: { region: [0, 0, 1, 1] } }"),
              HasSubstr("features.h.grow.element"));
  EXPECT_THAT(message("{ kind: wall, grow: { element: e.json } }"), HasSubstr("features.h.source"));
  EXPECT_THAT(message("{ kind: wall, source: r.gpkg, grow: { element: e.json, seeds: 2 } }"),
              HasSubstr("features.h.grow.seeds: unknown key"));
  EXPECT_THAT(message("{ kind: ditch, source: r.gpkg, conform: { corridor: 5 }, grow: { "
                      "element: e.json } }"),
              HasSubstr("features.h.conform: grown lines are drawn on the surface already"));
  EXPECT_THAT(message("{ kind: road, source: r.gpkg, grow: { element: e.json } }"),
              HasSubstr("features.h.width"));  // a road grown needs its width
}

TEST(GrownConfig, ABadElementSetFailsTheRunNamingTheKeyAndTheJsonKey) {
  test::TempDir dir;
  {
    std::ofstream bad(dir / "bad.json");
    bad << R"({"name": "x", "kind": "hedge", "seed_tag": "t", "elements": []})";
  }
  const PipelineConfig config = parse_pipeline(
      "version: 1\ngenerate: { width: 40, height: 40, pixel_size: 4 }\noutput: { dir: out }\n"
      "features:\n  h: { kind: hedge, grow: { element: bad.json, region: [500000, 4999900, "
      "500100, 5000000] } }\n",
      "t.yaml", dir.path());
  try {
    run_pipeline(config);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("features.h.grow.element"));
    EXPECT_THAT(e.what(), HasSubstr("bad.json"));
  }
  EXPECT_FALSE(fs::exists(dir / "out/report.json"));
}

// Issue #24 item 5: a grow mesh over kMaxGridCells is refused before anything is allocated or
// grown (it spent 221 s and 6.4 GB first), with the check `terraweave grow --resolution` meets
// on the same DEM, for any class, also one after a class that would grow.
TEST(GrownConfig, AMeshOverTheGridLimitIsRefusedBeforeAnythingGrows) {
  test::TempDir dir;
  const std::string element = (test::source_dir() / "samples/ornaments/hedge.json").string();
  const PipelineConfig config = parse_pipeline(
      fmt::format("version: 1\ngenerate: {{ width: 40, height: 40, pixel_size: 4 }}\n"
                  "output: {{ dir: out }}\nfeatures:\n"
                  "  fine: {{ kind: hedge, grow: {{ element: {0}, region: [500000, 4999900, "
                  "500100, 5000000] }} }}\n"
                  "  h: {{ kind: hedge, grow: {{ element: {0}, resolution: 0.001, region: "
                  "[500000, 4999900, 500100, 5000000] }} }}\n",
                  element),
      "t.yaml", dir.path());
  std::string message;
  try {
    run_pipeline(config);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_THAT(message, HasSubstr("features.h.grow.resolution: 0.001 m over the 160 x 160 m "
                                 "heightfield gives a 160000 x 160000 grid (95.4 GiB per float "
                                 "band); at most 1073741824 cells are allowed"));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Issue #21: on the demo DEM (90 m cells, UTM), hedges (2 m) and ditches (1 m) grow over two
// overlapping regions on a 10 m mesh, beside a road (6 m) and two streams (10 and 15 m): the
// footprints are narrower than the mesh's vertex spacing, so the mesh's mask alone lets lines
// through them. Checked here independently of the run's own check, with GEOS (OGR): no hedge
// footprint meets a ditch footprint, no line of a class crosses another of it (they may meet
// end to end), no footprint meets a road's or a stream's; report.json counts 0 crossings and
// the exact footprint test rejected candidates the mesh let through.
TEST(GrownCrossings, HedgesAndDitchesOverlappingOnTheDemoDemNeverCross) {
  test::TempDir dir;
  const std::string samples = (test::source_dir() / "samples").string();
  const std::string yaml = fmt::format(R"(
version: 1
seed: 7
heightfield: {0}/dem.tif
resolution: 5
resampling: cubic
region: [291200, 9114800, 291800, 9115400]
output: {{ dir: out, preview: false, exr: false }}
precedence: [rivers, roads, hedges, ditches]
features:
  rivers: {{ source: {0}/map.gpkg, layer: rivers, kind: river, width_attribute: width, width: 10 }}
  roads: {{ source: {0}/map.gpkg, layer: roads, kind: road, width_attribute: width, width: 6 }}
  hedges:
    kind: hedge
    grow: {{ element: {0}/ornaments/hedge.json, region: [291200, 9114800, 291650, 9115250],
            resolution: 10, seed: 7 }}
  ditches:
    kind: ditch
    grow: {{ element: {0}/ornaments/ditch.json, region: [291350, 9114950, 291800, 9115400],
            resolution: 10, seed: 7 }}
)",
                                       samples);
  const PipelineConfig config = parse_pipeline(yaml, "crossings.yaml", dir.path());
  const RunReport report = run_pipeline(config);
  ASSERT_TRUE(method_report<detail::GrownReport>(report));
  EXPECT_EQ(method_report<detail::GrownReport>(report)->crossings, 0);
  const nlohmann::json json = nlohmann::json::parse(test::read_file(dir / "out/report.json"));
  EXPECT_EQ(json["grown_crossings"].get<int>(), 0);
  int footprint_rejections = 0;
  for (const auto& c : json["classes"]) {
    if (!c.contains("grow")) continue;
    EXPECT_EQ(c["grow"]["crossings"]["grown"].get<int>(), 0) << c["name"];
    EXPECT_EQ(c["grow"]["crossings"]["feature"].get<int>(), 0) << c["name"];
    EXPECT_EQ(c["grow"]["crossings"]["forbidden"].get<int>(), 0) << c["name"];
    footprint_rejections += c["grow"]["rejected"]["footprint"].get<int>();
  }
  // The mesh's mask let candidates onto footprints; the exact test caught them.
  EXPECT_GT(footprint_rejections, 0);

  GDALAllRegister();
  std::unique_ptr<GDALDataset> gpkg(
      GDALDataset::Open((dir / "out/ornaments.gpkg").c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(gpkg);
  struct Footprint {
    std::string what;
    std::unique_ptr<OGRGeometry> line;
    double half_width = 0.0;
    int set = 0;
  };
  const auto footprint = [](const std::string& what, const OGRGeometry* g, double width, int set) {
    std::unique_ptr<OGRGeometry> flat(g->clone());
    flat->flattenTo2D();
    return Footprint{what, std::move(flat), 0.5 * width, set};
  };
  std::vector<Footprint> grown, features;
  for (auto [layer_name, width, set] :
       {std::tuple{"hedges", 2.0, 0}, std::tuple{"ditches", 1.0, 1}}) {
    OGRLayer* layer = gpkg->GetLayerByName(layer_name);
    ASSERT_TRUE(layer) << layer_name;
    for (const auto& f : *layer)
      grown.push_back(footprint(fmt::format("{} FID {}", layer_name, f->GetFID()),
                                f->GetGeometryRef(), width, set));
  }
  std::unique_ptr<GDALDataset> map(
      GDALDataset::Open((samples + "/map.gpkg").c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(map);
  OGREnvelope region;
  region.MinX = 291200, region.MinY = 9114800, region.MaxX = 291800, region.MaxY = 9115400;
  for (const char* layer_name : {"roads", "rivers"}) {
    for (const auto& f : *map->GetLayerByName(layer_name)) {
      OGREnvelope e;
      f->GetGeometryRef()->getEnvelope(&e);
      if (!e.Intersects(region)) continue;
      features.push_back(footprint(fmt::format("{} FID {}", layer_name, f->GetFID()),
                                   f->GetGeometryRef(), f->GetFieldAsDouble("width"), -1));
    }
  }
  int hedges = 0, ditches = 0;
  for (const Footprint& g : grown) ++(g.set == 0 ? hedges : ditches);
  std::printf("%d hedge lines, %d ditch lines, %zu roads and streams near\n", hedges, ditches,
              features.size());
  ASSERT_GT(hedges, 20);
  ASSERT_GT(ditches, 20);
  ASSERT_GE(features.size(), 2u);
  // A centimetre of slack: the run reads the features through its repair (duplicate points).
  constexpr double kSlack = 0.01;
  int near_features = 0;
  for (const Footprint& g : grown) {
    for (const Footprint& f : features) {
      const double d = g.line->Distance(f.line.get());
      EXPECT_GE(d, g.half_width + f.half_width - kSlack) << g.what << " onto " << f.what;
      near_features += d < g.half_width + f.half_width + 10.0;
    }
  }
  EXPECT_GT(near_features, 0);  // lines grew up to the features' footprints
  int near_other_class = 0;
  for (std::size_t i = 0; i < grown.size(); ++i) {
    const OGRLineString* a = grown[i].line->toLineString();
    for (std::size_t j = i + 1; j < grown.size(); ++j) {
      const OGRLineString* b = grown[j].line->toLineString();
      if (grown[i].set != grown[j].set) {
        const double d = a->Distance(b);
        EXPECT_GE(d, grown[i].half_width + grown[j].half_width)
            << grown[i].what << " onto " << grown[j].what;
        near_other_class += d < 10.0;
        continue;
      }
      if (!a->Intersects(b)) continue;
      // In a class lines meet only end to end, at a point that ends both.
      std::unique_ptr<OGRGeometry> common(a->Intersection(b));
      OGRPoint start_a, end_a, start_b, end_b;
      a->StartPoint(&start_a), a->EndPoint(&end_a), b->StartPoint(&start_b), b->EndPoint(&end_b);
      const bool joint = common && wkbFlatten(common->getGeometryType()) == wkbPoint &&
                         (common->Equals(&start_a) || common->Equals(&end_a)) &&
                         (common->Equals(&start_b) || common->Equals(&end_b));
      EXPECT_TRUE(joint) << grown[i].what << " crosses " << grown[j].what;
    }
  }
  EXPECT_GT(near_other_class, 0);  // the regions overlap: hedges and ditches meet there
}

// Issue #21: the check after growth counts what the growth should have refused and fails the
// run naming the lines; lines that only meet end to end (an ornament's joint) and keep their
// footprints apart pass with zero counts.
TEST(GrownCrossings, TheCheckCountsCrossingsAndFailsTheRunNamingTheLines) {
  PipelineConfig config;
  config.features.resize(3);
  config.features[0].name = "roads";
  config.features[1].name = "hedges";
  config.features[1].width = 2.0;
  method_options<GrowConfig>(config.features[1], kGrownMethodName);
  config.features[2].name = "ditches";
  config.features[2].width = 1.0;
  method_options<GrowConfig>(config.features[2], kGrownMethodName);
  std::vector<std::vector<LineFeature>> lines(3);
  LineFeature road;
  road.fid = 4;
  road.points = {{100.0, 0.0}, {100.0, 200.0}};
  road.width = 6.0;
  lines[0].push_back(road);
  const auto line = [](std::vector<Vec2> points) {
    GrownLine l;
    l.points = std::move(points);
    return l;
  };
  std::vector<detail::GrownClass> grown(2);
  grown[0].class_index = 1;
  grown[1].class_index = 2;
  // Hedges: FID 1 and 2 meet end to end at (50, 50); FID 3 ends 1.9 m from the road's centre
  // line (its 1 m half width and the road's 3 m overlap).
  grown[0].lines = {line({{10, 50}, {50, 50}}), line({{50, 50}, {60, 90}}),
                    line({{60, 20}, {98.1, 20}})};
  // Ditches: FID 1 1.4 m from hedge FID 1 (1 m + 0.5 m overlap), FID 2 1.6 m (apart).
  grown[1].lines = {line({{20, 51.4}, {40, 51.4}}), line({{20, 48.4}, {40, 48.4}})};
  std::vector<std::optional<detail::GrowthReport>> reports(3);
  reports[1].emplace();
  reports[2].emplace();
  try {
    detail::check_grown_lines(config.features, {}, lines, grown, {}, reports);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("grow: 2 grown crossings (1 between grown lines, 1 with "
                                    "features, 0 through nodata cells"));
    EXPECT_THAT(e.what(), HasSubstr("hedges FID 3 overlaps the footprint of roads FID 4"));
    EXPECT_THAT(e.what(), HasSubstr("ditches FID 1 overlaps hedges FID 1"));
  }
  EXPECT_EQ(reports[1]->crossings.feature, 1);
  EXPECT_EQ(reports[1]->crossings.grown, 0);
  EXPECT_EQ(reports[2]->crossings.grown, 1);  // a pair counts in the later class
  // Apart, and meeting only end to end: no error, zero counts.
  grown[0].lines[2] = line({{60, 20}, {95.9, 20}});
  grown[1].lines[0] = line({{20, 51.6}, {40, 51.6}});
  EXPECT_NO_THROW(detail::check_grown_lines(config.features, {}, lines, grown, {}, reports));
  EXPECT_EQ(reports[1]->crossings.feature, 0);
  EXPECT_EQ(reports[2]->crossings.grown, 0);
  // A hedge across another in its class is a crossing, not a joint.
  grown[0].lines.push_back(line({{30, 40}, {30, 60}}));
  EXPECT_THROW(detail::check_grown_lines(config.features, {}, lines, grown, {}, reports), Error);
  EXPECT_EQ(reports[1]->crossings.grown, 1);
}

}  // namespace
}  // namespace tw
