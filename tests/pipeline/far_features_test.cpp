// Real country-scale data over the small UTM 25S sample DEM (issue #21 items 2 and 9): a
// continent polygon reaching Alaska and the Seychelles and the world's national borders (GSHHG)
// as `existing`, as line classes and as an area class run to the end; and the run's
// report.json accounts for its whole time in named stages.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The land polygon's rings as one MultiLineString (the coast of the Americas and the
// Seychelles), lon/lat, for a line class.
void write_coast(const fs::path& land, const fs::path& out) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> in(GDALDataset::Open(land.c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(in);
  OGRLayer* layer = in->GetLayer(0);
  OGRFeatureUniquePtr feature(layer->GetNextFeature());
  std::unique_ptr<OGRGeometry> coast(feature->GetGeometryRef()->Boundary());
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GeoJSON");
  std::unique_ptr<GDALDataset> written(driver->Create(out.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  OGRLayer* lines = written->CreateLayer("coast", layer->GetSpatialRef(), wkbMultiLineString);
  OGRFeature line(lines->GetLayerDefn());
  line.SetFID(1);
  line.SetGeometry(coast.get());
  ASSERT_EQ(lines->CreateFeature(&line), OGRERR_NONE);
}

class FarFeatures : public ::testing::Test {
 protected:
  // One run for the suite: its output is what both tests read.
  static void SetUpTestSuite() {
    dir = new test::TempDir;
    const fs::path src = test::source_dir();
    write_coast(src / "tests/data/dcw_americas.geojson", *dir / "coast.geojson");
    std::ofstream(*dir / "pipeline.yaml") << fmt::format(R"(version: 1
seed: 7
heightfield: {0}/samples/dem.tif
resolution: 30
output: {{ dir: out, exr: false, geotiff: true, preview: true }}
features:
  roads: {{ source: {0}/samples/map.gpkg, layer: roads, kind: road, width: 6 }}
  coast: {{ source: coast.geojson, kind: river, width: 20 }}
  borders: {{ source: {0}/tests/data/gshhg_borders.geojson, kind: road, width: 6 }}
  land:
    kind: area
    source: {0}/tests/data/dcw_americas.geojson
    sketch: {0}/samples/sketches/orchard.geojson
    scale: 1000
existing:
  - {{ source: {0}/tests/data/dcw_americas.geojson }}
  - {{ source: {0}/tests/data/gshhg_borders.geojson, width: 10 }}
)",
                                                         src.string());
    result = new test::CommandResult(test::run_command("cd '" + dir->path().string() + "' && '" +
                                                       test::terraweave_binary().string() +
                                                       "' run pipeline.yaml"));
  }
  static void TearDownTestSuite() {
    delete result;
    delete dir;
  }
  static nlohmann::json report() {
    return nlohmann::json::parse(test::read_file(*dir / "out/report.json"));
  }
  static test::TempDir* dir;
  static test::CommandResult* result;
};
test::TempDir* FarFeatures::dir = nullptr;
test::CommandResult* FarFeatures::result = nullptr;

// Before: "features.coast: coast.geojson:coast: FID 1: cannot reproject into the grid's CRS:
// Point outside of projection domain" and nothing written.
TEST_F(FarFeatures, ContinentAndWorldBordersRunAsExistingLineAndAreaClasses) {
  const test::CommandResult& r = *result;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("existing: 1 polygons, 0 lines"));
  const nlohmann::json report = FarFeatures::report();
  std::map<std::string, std::string> codes;  // subject -> code
  for (const nlohmann::json& w : report["warnings"]) {
    codes[w["subject"].get<std::string>()] = w["code"].get<std::string>();
    EXPECT_NE(w["code"], "dropped_part") << w.dump();
  }
  // Far from the DEM: the coast (11 km east of it) and every border; said, not failed.
  EXPECT_EQ(codes["features.coast"], "empty_class");
  EXPECT_EQ(codes["features.borders"], "empty_class");
  EXPECT_EQ(codes["existing.1"], "empty_source");
  EXPECT_FALSE(codes.contains("existing.0"));  // the land covers the DEM: kept
  ASSERT_EQ(report["areas"].size(), 1u);
  ASSERT_EQ(report["areas"][0]["features"].size(), 1u);
  EXPECT_EQ(report["areas"][0]["features"][0]["fid"], 1);
  // The whole DEM (80 x 80 cells of about 90 m) lies on the land.
  EXPECT_GT(report["areas"][0]["features"][0]["area_m2"].get<double>(), 0.99 * 7200.0 * 7200.0);
}

// Every stage that takes time has its timing: the named stages add up to the total within 5 %,
// and what no stage measured is the stage `untimed`, so that all of them add up to the total.
TEST_F(FarFeatures, StageTimingsAccountForTheWholeRun) {
  ASSERT_EQ(result->exit_code, 0) << result->output;
  const nlohmann::json report = FarFeatures::report();
  const double total = report["timings"]["total_seconds"];
  double named = 0.0, all = 0.0;
  std::set<std::string> stages;
  for (const nlohmann::json& s : report["timings"]["stages"]) {
    const std::string name = s["stage"];
    EXPECT_TRUE(stages.insert(name).second) << name << " twice";
    all += s["seconds"].get<double>();
    if (name != "untimed") named += s["seconds"].get<double>();
  }
  for (const char* stage :
       {"setup", "ingest", "ribbons", "terrain", "areas", "plan", "inputs", "render", "layers",
        "preview", "features.geojson", "placements", "areas.gpkg", "manifest"})
    EXPECT_TRUE(stages.contains(stage)) << stage;
  EXPECT_GT(total, 0.0);
  EXPECT_NEAR(all, total, 1e-9 * total + 1e-12);
  EXPECT_GE(named, 0.95 * total) << report["timings"]["stages"].dump();
  EXPECT_LE(named, total * (1 + 1e-9));
}

}  // namespace
}  // namespace tw
