// Exemplar networks (docs/networks.md, "Exemplars"): OGR and SVG reading, the repairs and the
// planar graph, and the errors that name file, key and FID.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "network/exemplar.hpp"
#include "network/stats.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string geojson(const std::vector<std::string>& coordinates) {
  std::string features;
  for (std::size_t i = 0; i < coordinates.size(); ++i)
    features += std::string(i ? "," : "") + R"({"type":"Feature","id":)" + std::to_string(i + 1) +
                R"(,"properties":{},"geometry":{"type":"LineString","coordinates":)" +
                coordinates[i] + "}}";
  return R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"EPSG:32631"}},"features":[)" +
         features + "]}";
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(NetworkExemplar, CrossingsBecomeJunctionsNearMissesSnapDuplicatesDrop) {
  test::TempDir dir;
  // A cross, a line ending 0.5 m short of the vertical one, and an exact duplicate.
  const std::string path = write(dir, "lines.geojson",
                                 geojson({"[[0,50],[100,50]]", "[[50,0],[50,100]]",
                                          "[[50.5,80],[100,80]]", "[[0,50],[100,50]]"}));
  Warnings warnings;
  const NetworkLines lines = read_network_lines({.source = path}, warnings);
  ASSERT_EQ(lines.lines.size(), 4u);
  const Network net = build_planar_network(lines, 1.0, "exemplar", warnings);
  std::vector<int> degree = net.degrees();
  std::sort(degree.begin(), degree.end());
  // Ends: 4 of the cross + 1 of the snapped line; the cross's centre (4) and the T (3).
  EXPECT_EQ(degree, (std::vector<int>{1, 1, 1, 1, 1, 3, 4}));
  EXPECT_EQ(net.edges.size(), 6u);
  bool snapped = false, duplicate = false;
  for (const Warning& w : warnings.list()) {
    snapped = snapped || (w.code == "snapped_end" && w.fid == 3);
    duplicate = duplicate || (w.code == "duplicate_line" && w.fid == 4);
  }
  EXPECT_TRUE(snapped);
  EXPECT_TRUE(duplicate);
}

TEST(NetworkExemplar, ChainsThroughBendsAreOneEdge) {
  test::TempDir dir;
  const std::string path =
      write(dir, "chain.geojson",
            geojson({"[[0,0],[10,0]]", "[[10,0],[20,5]]", "[[20,5],[30,0],[40,0]]"}));
  Warnings warnings;
  const Network net = build_planar_network(read_network_lines({.source = path}, warnings), 0.1,
                                           "exemplar", warnings);
  ASSERT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.edges[0].points.size(), 5u);
  EXPECT_NEAR(net.total_length(), 10 + std::hypot(10, 5) * 2 + 10, 1e-9);
}

TEST(NetworkExemplar, BadInputIsOneLineNamingFileAndFid) {
  test::TempDir dir;
  const std::string empty = write(dir, "empty.geojson", geojson({}));
  Warnings w;
  EXPECT_NE(
      error_of([&] { read_network_lines({.source = empty}, w); }).find("empty.geojson: no lines"),
      std::string::npos);
  const std::string single = write(dir, "single.geojson", geojson({"[[0,0],[5,5]]"}));
  const std::string e = error_of([&] { read_network_lines({.source = single}, w); });
  EXPECT_NE(e.find("single.geojson: FID 1: a single line"), std::string::npos) << e;
  const std::string svg =
      write(dir, "bad.svg", R"(<svg><path d="M 0 0 L 10 0"/><circle cx="1" cy="1" r="2"/></svg>)");
  const std::string s = error_of([&] { read_network_lines({.source = svg}, w); });
  EXPECT_NE(s.find("bad.svg: element 1 <circle>: not supported"), std::string::npos) << s;
  const std::string arc = write(dir, "arc.svg", R"(<svg><path d="M 0 0 A 5 5 0 0 1 10 0"/></svg>)");
  EXPECT_NE(error_of([&] { read_network_lines({.source = arc}, w); }).find("path command 'A'"),
            std::string::npos);
}

// What the exemplar reader's fuzz target (fuzz/network_exemplar.cpp) found: numbers that are no
// coordinates, path data without a moveto, attributes without quotes.
TEST(NetworkExemplar, NumbersOutOfRangeAndPathsWithoutMovetoAreRefused) {
  test::TempDir dir;
  Warnings w;
  const auto message = [&](const char* name, const std::string& text) {
    const std::string path = write(dir, name, text);
    return error_of([&] { read_network_lines({.source = path}, w); });
  };
  EXPECT_NE(message("inf.svg", R"(<svg><path d="M 0 0 L 1e999 0"/><path d="M 0 1 L 5 1"/></svg>)")
                .find("inf.svg: element 0 <path>: a number out of range: 1e999"),
            std::string::npos);
  EXPECT_NE(message("nan.svg", R"(<svg><line x1="nan" y1="0" x2="1" y2="1"/></svg>)")
                .find("nan.svg: element 0 <line>: a number out of range: nan"),
            std::string::npos);
  EXPECT_NE(message("lineto.svg", R"(<svg><path d="L 5 5"/></svg>)")
                .find("lineto.svg: element 0 <path>: path data must start with a moveto"),
            std::string::npos);
  EXPECT_NE(message("unquoted.svg", R"(<svg><path d=M 0 0 L 5 5/><path d/></svg>)")
                .find("unquoted.svg: no lines"),
            std::string::npos);
  EXPECT_NE(message("big.geojson", geojson({"[[0,0],[5,5]]", "[[0,5],[1e999,0]]"}))
                .find("big.geojson: FID 2: a coordinate that is not a finite number"),
            std::string::npos);
}

TEST(NetworkExemplar, SvgPathsAreScaledNorthUp) {
  Warnings w;
  const NetworkLines lines = read_network_lines(
      {.source = (test::source_dir() / "tests/data/network_drawn.svg").string(), .scale = 2.0}, w);
  EXPECT_EQ(lines.lines.size(), 16u);
  // The first path starts at (0, 200) in SVG units: (0, -400) m north-up at scale 2.
  EXPECT_DOUBLE_EQ(lines.lines[0].front().x, 0.0);
  EXPECT_DOUBLE_EQ(lines.lines[0].front().y, -400.0);
  const Network net = build_planar_network(lines, 1.0, "exemplar", w);
  int junctions = 0;
  for (int d : net.degrees()) junctions += d >= 3;
  EXPECT_GE(junctions, 15);
}

TEST(NetworkExemplar, RealCountyBoundariesCutByARegion) {
  const std::string nc = (test::source_dir() / "tests/data/nc_counties.geojson").string();
  test::TempDir dir;
  // A box in the local metric frame the geographic shapefile is read in (centre of its extent).
  Warnings w;
  const NetworkLines all = read_network_lines({.source = nc}, w);
  const std::string region = write(
      dir, "cut.geojson",
      R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[-80.5,35],[-78.5,35],[-78.5,36.2],[-80.5,36.2],[-80.5,35]]]}}]})");
  const NetworkLines cut = read_network_lines({.source = nc, .region = region}, w);
  ASSERT_FALSE(cut.region.empty());
  EXPECT_LT(cut.lines.size(), all.lines.size());
  const Network net = build_planar_network(cut, 1.0, "exemplar", w);
  int boundary = 0;
  for (char b : net.on_boundary) boundary += b;
  EXPECT_GT(boundary, 10);  // lines cut by the box end on it: cuts, not dangling ends
  EXPECT_EQ(network_stats(net).dangling, 0);
}

TEST(NetworkStats, NormalizedW1) {
  EXPECT_DOUBLE_EQ(normalized_w1({1, 2, 3, 4}, {1, 2, 3, 4}), 0.0);
  // A shift by one standard deviation of the reference is 1.
  const std::vector<double> a{0, 2};
  EXPECT_NEAR(normalized_w1(a, {1, 3}), 1.0, 1e-12);
}

}  // namespace
}  // namespace tw
