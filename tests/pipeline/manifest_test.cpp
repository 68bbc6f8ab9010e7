// report.json as a manifest a nightly job can trust, and `terraweave diff` (issue #12 item 4):
// format and schema, the resolved configuration and its overrides, hashes and sizes of every
// input and output, height ranges, per-feature earthwork; timings apart; and a diff that
// names the layers that changed with the largest difference, computed here independently.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::Contains;
using ::testing::HasSubstr;

const char* const kPipeline = R"(version: 1
seed: 3
generate: { width: 64, height: 48, pixel_size: 10, relief: 60, origin: [500000, 5000000] }
output: { dir: out, preview: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6,
           profile: { max_grade: 0.05 } }
)";

std::string xxh3_hex(const std::string& bytes) {
  XXH128_canonical_t c;
  XXH128_canonicalFromHash(&c, XXH3_128bits(bytes.data(), bytes.size()));
  std::string hex;
  for (const unsigned char b : c.digest) hex += fmt::format("{:02x}", b);
  return hex;
}

std::vector<float> read_band(const fs::path& path, int band = 1) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  if (!ds) ADD_FAILURE() << path;
  const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
  std::vector<float> v(std::size_t(w) * h);
  EXPECT_EQ(
      ds->GetRasterBand(band)->RasterIO(GF_Read, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0),
      CE_None);
  return v;
}

// What the diff must say about one band: the count of differing pixels and the largest
// difference with its place (first in row order), as "N pixels differ, largest X at col C row R".
std::string expected_band_line(const std::vector<float>& a, const std::vector<float>& b,
                               int width) {
  std::int64_t differing = 0;
  double largest = 0.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i]) continue;
    ++differing;
    const double d = std::abs(double(a[i]) - double(b[i]));
    if (d > largest) largest = d, at = i;
  }
  return fmt::format("{} pixels differ, largest {:.9g} at col {} row {}", differing, largest,
                     at % width, at / width);
}

class Manifest : public ::testing::Test {
 protected:
  void SetUp() override {
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500050 4999600, 500300 4999800, 500600 4999700)", 6.0}});
    std::ofstream(dir / "pipeline.yaml") << kPipeline;
  }

  CommandResult terraweave(const std::string& args) {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args);
  }
  json report(const std::string& run) { return json::parse(read_file(dir / run / "report.json")); }

  TempDir dir;
};

TEST_F(Manifest, ReportNamesFormatConfigHashesAndHeights) {
  const CommandResult r = terraweave("run pipeline.yaml --out a --set features.roads.width=8 -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json j = report("a");
  EXPECT_EQ(j["format"], "terraweave-report");
  EXPECT_EQ(j["version"]["schema"], 2);
  EXPECT_TRUE(j["version"]["terraweave"].is_string());
  for (const char* lib : {"gdal", "proj", "openimageio"}) EXPECT_TRUE(j["versions"].contains(lib));
  EXPECT_EQ(j["config"]["features"]["roads"]["width"], 8);  // after --set
  EXPECT_EQ(j["config"]["generate"]["width"], 64);
  EXPECT_EQ(j["overrides"], json::array({"features.roads.width=8"}));
  // Timings in one place only, so that the rest diffs cleanly.
  EXPECT_FALSE(j.contains("stages"));
  EXPECT_FALSE(j.contains("total_seconds"));
  EXPECT_FALSE(j["classes"][0].contains("ingest_seconds"));
  EXPECT_TRUE(j["timings"].contains("stages"));
  EXPECT_THAT(j["timings"]["started_utc"].get<std::string>(),
              ::testing::MatchesRegex("20[0-9][0-9]-[01][0-9]-[0-3][0-9]T[0-9:]+Z"));

  ASSERT_EQ(j["inputs"].size(), 1u);  // the generated heightfield is no file
  EXPECT_EQ(j["inputs"][0]["role"], "vector");
  const std::string map = read_file(dir / "map.gpkg");
  EXPECT_EQ(j["inputs"][0]["bytes"], map.size());
  EXPECT_EQ(j["inputs"][0]["xxh3_128"], xxh3_hex(map));
  std::vector<std::string> names;
  for (const json& f : j["outputs"]) {
    names.push_back(f["path"]);
    const std::string bytes = read_file(dir / "a" / f["path"].get<std::string>());
    EXPECT_EQ(f["bytes"], bytes.size()) << f["path"];
    EXPECT_EQ(f["xxh3_128"], xxh3_hex(bytes)) << f["path"];
  }
  EXPECT_THAT(names, Contains("height.tif"));
  EXPECT_THAT(names, Contains("splat.exr"));
  // 3 layers x (EXR, GeoTIFF) and features.geojson; report.json is not in its own list.
  EXPECT_EQ(names.size(), 7u);

  const std::vector<float> height = read_band(dir / "a/height.tif");
  const auto [lo, hi] = std::minmax_element(height.begin(), height.end());
  EXPECT_EQ(j["height_range"]["output"][0].get<float>(), *lo);
  EXPECT_EQ(j["height_range"]["output"][1].get<float>(), *hi);
  EXPECT_LT(j["height_range"]["input"][0].get<float>(), j["height_range"]["input"][1].get<float>());
  const json& road = j["classes"][0]["features"][0];
  EXPECT_GT(road["grade_max"].get<double>(), 0.0);
  EXPECT_LE(road["grade_max"].get<double>(), 0.05 + 1e-6);  // profile.max_grade holds
  EXPECT_GT(road["cut_max_m"].get<double>() + road["fill_max_m"].get<double>(), 0.0);
}

TEST_F(Manifest, DiffOfTwoRunsOfTheSameInputsIsEmpty) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out a").exit_code, 0);
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out b --threads 1").exit_code, 0);
  const CommandResult r = terraweave("diff a b");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(lines_of(r.output), std::vector<std::string>{"identical"});
}

TEST_F(Manifest, DiffOfAWiderRoadNamesTheLayersAndTheLargestDifference) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out a").exit_code, 0);
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out b --set features.roads.width=14").exit_code, 0);
  const CommandResult r = terraweave("diff a b");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const std::vector<std::string> lines = lines_of(r.output);
  EXPECT_THAT(r.output, HasSubstr("height.tif height: " +
                                  expected_band_line(read_band(dir / "a/height.tif"),
                                                     read_band(dir / "b/height.tif"), 64)));
  // splat band 2 is splat.road
  EXPECT_THAT(r.output, HasSubstr("splat.tif splat.road: " +
                                  expected_band_line(read_band(dir / "a/splat.tif", 2),
                                                     read_band(dir / "b/splat.tif", 2), 64)));
  EXPECT_THAT(r.output, HasSubstr("avoidance.tif forbidden: "));
  EXPECT_THAT(lines, Contains("report.json /config/features/roads/width: 6 -> 14"));
  EXPECT_THAT(r.output, HasSubstr("report.json /classes/0/features/0/width_m: 6.0 -> 14.0"));
}

TEST_F(Manifest, DiffOfAnotherSeedSeesAnotherGeneratedWorld) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out a").exit_code, 0);
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out b --seed 4").exit_code, 0);
  EXPECT_EQ(report("b")["seed"], 4);
  EXPECT_EQ(report("b")["overrides"], json::array({"seed=4"}));
  const CommandResult r = terraweave("diff a b");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("height.tif height: " +
                                  expected_band_line(read_band(dir / "a/height.tif"),
                                                     read_band(dir / "b/height.tif"), 64)));
  EXPECT_THAT(r.output, HasSubstr("report.json /seed: 3 -> 4"));
}

TEST_F(Manifest, DiffOfAFolderWithoutAReportIsTrouble) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --out a").exit_code, 0);
  fs::create_directories(dir / "empty");
  const CommandResult r = terraweave("diff a empty");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(lines_of(r.output),
              ::testing::ElementsAre(HasSubstr("empty: no report.json: not the output folder")));
}

}  // namespace
}  // namespace tw::test
