// Incremental rebuilds with --cache (docs/cache.md, issue #10 item 3) on a small generated world
// with five roads: one changed road rebuilds exactly the syntheses whose inputs changed (worked
// out here from the geometry, independently of the cache), a corrupt entry is detected and
// rebuilt, and every output equals a clean run's, byte for byte.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr double kX0 = 500000.0, kY0 = 5000000.0;  // south-west corner of the world
constexpr double kWidth = 6.0;                     // every road's width
constexpr double kSynthesisWidth = 8.0;

constexpr const char* kPipeline = R"(
version: 1
seed: 5
generate: { width: 160, height: 160, pixel_size: 4, relief: 40, origin: [500000, 5000640] }
synthesis_resolution: 1
features:
  roads:
    source: roads.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis: { exemplar: cobble.png, width: 8, scale: 5, delta: 8 }
)";

using Line = std::vector<Vec2>;  // local metres from (kX0, kY0)

// FID 1..5 in this order (the synthesis order). R1 and R2 cross; R4 runs beside R1's east end,
// 18 m north of it; R3 and R5 are far from everything.
std::vector<Line> roads() {
  return {{{50, 300}, {590, 300}},
          {{320, 50}, {320, 590}},
          {{50, 450}, {250, 450}},
          {{450, 318}, {590, 318}},
          {{50, 100}, {250, 100}}};
}

// R1 with its east end moved 10 m north: now 8 m from R4 there.
std::vector<Line> roads_with_r1_moved() {
  std::vector<Line> lines = roads();
  lines[0][1] = {590, 310};
  return lines;
}

void write_roads(const fs::path& path, const std::vector<Line>& lines) {
  std::vector<test::VectorFeature> features;
  for (const Line& line : lines) {
    std::ostringstream wkt;
    wkt.precision(12);
    wkt << "LINESTRING (";
    for (std::size_t i = 0; i < line.size(); ++i)
      wkt << (i ? ", " : "") << kX0 + line[i].x << ' ' << kY0 + line[i].y;
    wkt << ")";
    features.emplace_back(wkt.str(), kWidth);
  }
  fs::remove(path);
  test::write_layer(path, "roads", features);
}

// --- The expected rebuilds, from the geometry alone ------------------------------------------
// A synthesis reads its canvas: the ribbon's box plus a cell, here within half the synthesis
// width plus 2 m of the line's box. It is rebuilt when its own line changed, when a junction
// (a crossing of two lines) on its canvas moved, appeared or went, or when a feature synthesized
// before it whose canvas met its own (before or after the change) was rebuilt.
struct Box {
  double x0, y0, x1, y1;
  bool meets(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool holds(Vec2 p, double grow) const {
    return p.x > x0 - grow && p.x < x1 + grow && p.y > y0 - grow && p.y < y1 + grow;
  }
};

Box canvas_box(const Line& line) {
  Box b{1e9, 1e9, -1e9, -1e9};
  for (const Vec2 p : line)
    b = {std::min(b.x0, p.x), std::min(b.y0, p.y), std::max(b.x1, p.x), std::max(b.y1, p.y)};
  const double grow = kSynthesisWidth / 2 + 2.0;
  return {b.x0 - grow, b.y0 - grow, b.x1 + grow, b.y1 + grow};
}

std::optional<Vec2> crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double den = cross(b - a, d - c);
  if (den == 0.0) return std::nullopt;
  const double t = cross(c - a, d - c) / den, u = cross(c - a, b - a) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return std::nullopt;
  return a + (b - a) * t;
}

std::vector<Vec2> crossings(const std::vector<Line>& lines) {
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = i + 1; j < lines.size(); ++j)
      for (std::size_t s = 0; s + 1 < lines[i].size(); ++s)
        for (std::size_t t = 0; t + 1 < lines[j].size(); ++t)
          if (auto p = crossing(lines[i][s], lines[i][s + 1], lines[j][t], lines[j][t + 1]))
            points.push_back(*p);
  return points;
}

std::set<int> expected_rebuilds(const std::vector<Line>& before, const std::vector<Line>& after) {
  const std::vector<Vec2> old_junctions = crossings(before), new_junctions = crossings(after);
  std::vector<Vec2> moved;  // in one set and not the other
  for (const Vec2 p : old_junctions)
    if (std::find(new_junctions.begin(), new_junctions.end(), p) == new_junctions.end())
      moved.push_back(p);
  for (const Vec2 p : new_junctions)
    if (std::find(old_junctions.begin(), old_junctions.end(), p) == old_junctions.end())
      moved.push_back(p);
  const double disc = kSynthesisWidth / 2 + 1.0;  // the widest member's half width + a cell
  std::set<int> rebuilt;
  for (std::size_t f = 0; f < after.size(); ++f) {
    const Box old_box = canvas_box(before[f]), new_box = canvas_box(after[f]);
    bool changed = before[f] != after[f];
    for (const Vec2 p : moved)
      changed = changed || old_box.holds(p, disc) || new_box.holds(p, disc);
    for (std::size_t g = 0; g < f; ++g) {
      if (!rebuilt.count(int(g) + 1)) continue;
      for (const Box& mine : {old_box, new_box})
        for (const Box& theirs : {canvas_box(before[g]), canvas_box(after[g])})
          changed = changed || mine.meets(theirs);
    }
    if (changed) rebuilt.insert(int(f) + 1);
  }
  return rebuilt;
}

// --- Runs ---------------------------------------------------------------------------------------
class CacheRun : public ::testing::Test {
 protected:
  void SetUp() override {
    write_roads(dir_ / "roads.gpkg", roads());
    const fs::path exemplars = test::source_dir() / "samples/exemplars";
    test::crop_raster(exemplars / "cobble_edging_200x56.png", dir_ / "cobble.png", "PNG", 60, 56);
    test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir_ / "cobble_height.tif",
                      "GTiff", 60, 56);
  }

  RunReport run(const std::string& out, bool with_cache = true) {
    const PipelineConfig config = parse_pipeline(kPipeline, "cache.yaml", dir_.path(),
                                                 {{"output.dir", (dir_ / out).string()}});
    RunOptions options;
    if (with_cache) options.cache_dir = dir_ / "cache";
    return run_pipeline(config, options);
  }

  // FID -> cache status of each road, as report.json lists them.
  std::map<std::int64_t, nlohmann::json> statuses(const std::string& out) const {
    std::ifstream in(dir_ / out / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    std::map<std::int64_t, nlohmann::json> by_fid;
    for (const auto& f : report["classes"][0]["features"]) by_fid[f["fid"]] = f["cache"];
    return by_fid;
  }

  std::set<int> rebuilt(const std::string& out) const {
    std::set<int> fids;
    for (const auto& [fid, cache] : statuses(out))
      if (cache["status"] == "rebuilt") fids.insert(int(fid));
    return fids;
  }

  // Every output but report.json (timings, cache statuses), by name, read through the links.
  std::map<std::string, std::string> outputs(const std::string& out) const {
    std::map<std::string, std::string> files;
    const fs::path root = dir_ / out;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::end(it); ++it) {
      const std::string name = it->path().lexically_relative(root).string();
      if (name == ".terraweave") {
        it.disable_recursion_pending();
        continue;
      }
      if (fs::is_directory(it->path()) || name == "report.json") continue;
      files[name] = test::read_file(it->path());
    }
    return files;
  }

  void expect_same_outputs(const std::string& a, const std::string& b) const {
    const auto x = outputs(a), y = outputs(b);
    ASSERT_GT(x.size(), 5u);
    ASSERT_EQ(x.size(), y.size());
    for (const auto& [name, bytes] : x) {
      ASSERT_TRUE(y.count(name)) << name;
      EXPECT_TRUE(bytes == y.at(name)) << name << " differs between " << a << " and " << b;
    }
  }

  test::TempDir dir_;
};

TEST_F(CacheRun, ExpectedRebuildsOfTheTestGeometry) {
  // The change touches R1, its crossing with R2, and brings R1's canvas onto R4's.
  EXPECT_EQ(expected_rebuilds(roads(), roads_with_r1_moved()), (std::set<int>{1, 2, 4}));
}

TEST_F(CacheRun, WithoutCacheEveryFeatureIsRebuiltAndKeyed) {
  run("plain", false);
  for (const auto& [fid, cache] : statuses("plain")) {
    EXPECT_EQ(cache["status"], "rebuilt") << fid;
    EXPECT_EQ(cache["why"], "no cache") << fid;
    EXPECT_EQ(cache["key"].get<std::string>().size(), 32u) << fid;
  }
}

TEST_F(CacheRun, UnchangedRerunReusesEverythingWithTheSameBytes) {
  run("first");
  EXPECT_EQ(rebuilt("first"), (std::set<int>{1, 2, 3, 4, 5}));
  for (const auto& [fid, cache] : statuses("first")) EXPECT_EQ(cache["why"], "new") << fid;
  run("second");
  EXPECT_EQ(rebuilt("second"), std::set<int>{});
  for (const auto& [fid, cache] : statuses("second")) {
    EXPECT_EQ(cache["why"], "unchanged") << fid;
    EXPECT_EQ(cache["key"], statuses("first")[fid]["key"]) << fid;
  }
  expect_same_outputs("first", "second");
}

TEST_F(CacheRun, OneChangedRoadRebuildsExactlyWhatItReaches) {
  run("before");
  write_roads(dir_ / "roads.gpkg", roads_with_r1_moved());
  run("after");
  const std::set<int> expected = expected_rebuilds(roads(), roads_with_r1_moved());
  EXPECT_EQ(rebuilt("after"), expected);
  const auto status = statuses("after");
  EXPECT_EQ(status.at(1)["why"], "geometry changed");
  EXPECT_EQ(status.at(2)["why"], "avoidance changed");  // the junction disc moved
  EXPECT_EQ(status.at(4)["why"], "earlier feature changed");
  EXPECT_EQ(status.at(3)["why"], "unchanged");
  run("clean", false);
  expect_same_outputs("after", "clean");
}

TEST_F(CacheRun, CorruptEntriesAreDetectedAndRebuilt) {
  run("first");
  const auto keys = statuses("first");
  const auto entry = [&](std::int64_t fid) {
    return dir_ / "cache/synthesis" / (keys.at(fid)["key"].get<std::string>() + ".twc");
  };
  ASSERT_TRUE(fs::exists(entry(3)));
  {  // one byte of R3's entry flipped, in its placements
    std::string bytes = test::read_file(entry(3));
    bytes[bytes.size() / 2] ^= 0x20;
    std::ofstream(entry(3), std::ios::binary | std::ios::trunc) << bytes;
  }
  fs::resize_file(entry(5), fs::file_size(entry(5)) - 7);  // R5's truncated
  const RunReport report = run("second");
  const auto status = statuses("second");
  EXPECT_EQ(status.at(3)["status"], "rebuilt");
  EXPECT_EQ(status.at(3)["why"], "corrupt entry");
  EXPECT_EQ(status.at(5)["why"], "corrupt entry");
  EXPECT_EQ(rebuilt("second"), (std::set<int>{3, 5}));
  int corrupt = 0;
  for (const Warning& w : report.warnings) {
    if (w.code != "cache_corrupt") continue;
    ++corrupt;
    EXPECT_THAT(w.message, HasSubstr(".twc"));
  }
  EXPECT_EQ(corrupt, 2);
  expect_same_outputs("first", "second");
  run("third");  // the rebuilt entries are whole again
  EXPECT_EQ(rebuilt("third"), std::set<int>{});
  expect_same_outputs("first", "third");
}

}  // namespace
}  // namespace tw
