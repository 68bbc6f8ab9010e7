#include "ornament/element.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "core/error.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& json) {
  try {
    parse_element_set(json, "bad.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal = R"({"name": "n", "kind": "hedge", "seed_tag": "a", "elements": [
  {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,0],[3,0]]}]}]})";

TEST(Element, SamplesReadWithTheirGrowthPointsOnSplineEnds) {
  for (const char* name : {"hedge", "wall", "trail", "ditch"}) {
    const ElementSet set =
        read_element_set(test::source_dir() / "samples/ornaments" / (std::string(name) + ".json"));
    EXPECT_EQ(set.kind, name);
    EXPECT_GE(set.elements.size(), 2u) << name;
    EXPECT_FALSE(elements_with_tag(set, set.seed_tag).empty()) << name;
  }
  const ElementSet hedge = read_element_set(test::source_dir() / "samples/ornaments/hedge.json");
  const DecorativeElement& gate = hedge.elements[1];
  EXPECT_EQ(gate.name, "gate");
  ASSERT_EQ(gate.splines.size(), 3u);
  ASSERT_EQ(gate.growth_points.size(), 2u);
  EXPECT_NEAR(gate.growth_points[1].angle, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(gate.growth_points[1].at, (Vec2{0.45, 0.6}));
  EXPECT_EQ(hedge.elements[0].sizes, (std::vector<double>{0.6, 1.0, 1.4}));
  EXPECT_DOUBLE_EQ(hedge.scale_m, 20.0);
}

TEST(Element, PlanarPolylineInterpolatesTheEndsAndFollowsTheCubic) {
  BezierSpline s{"x", {{0, 0}, {1, 1}, {2, 1}, {3, 0}}};
  const std::vector<Vec2> line = planar_polyline(s, 4);
  ASSERT_EQ(line.size(), 5u);
  EXPECT_EQ(line.front(), (Vec2{0, 0}));
  EXPECT_EQ(line.back(), (Vec2{3, 0}));
  EXPECT_DOUBLE_EQ(line[2].x, 1.5);   // symmetric control polygon: midpoint at x = 1.5
  EXPECT_DOUBLE_EQ(line[2].y, 0.75);  // 3/4 of the control height
}

TEST(Element, MinimalSetParses) {
  const ElementSet set = parse_element_set(kMinimal, "ok.json");
  EXPECT_EQ(set.elements.at(0).sizes, std::vector<double>{1.0});
  EXPECT_DOUBLE_EQ(set.scale_m, 10.0);
}

TEST(Element, ErrorsNameTheFileAndTheKey) {
  EXPECT_THAT(error_of("{"), HasSubstr("bad.json: not valid JSON"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "fence", "seed_tag": "a", "elements": []})"),
              HasSubstr("bad.json: key 'kind': 'fence' is not one of"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,0]]}]}]})"),
              HasSubstr("key 'elements[0].splines[0].points': a cubic spline needs 3n + 1"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,"x"],[3,0]]}]}]})"),
              HasSubstr("key 'elements[0].splines[0].points[2][1]': expected a number"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[1,0],[1,1],[2,0],[3,0]]}]}]})"),
              HasSubstr("key 'elements[0].splines': no spline starts or ends at the origin"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,0],[3,0]]}],
       "growth_points": [{"tag": "a", "at": [1, 0]}]}]})"),
              HasSubstr("key 'elements[0].growth_points[0].at': not the end of one of"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,0],[3,0]]}],
       "growth_points": [{"tag": "leaf", "at": [3, 0]}]}]})"),
              HasSubstr("key 'elements[0].growth_points[0].tag': no element has tag 'leaf'"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "b", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[1,0],[2,0],[3,0]]}]}]})"),
              HasSubstr("key 'seed_tag': no element has tag 'b'"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "wall", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "sizes": [1, -2],
       "splines": [{"points": [[0,0],[1,0],[2,0],[3,0]]}]}]})"),
              HasSubstr("key 'elements[0].sizes[1]': a size must be > 0"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "hedge", "seed_tag": "a", "elements": [
      {"name": "e", "tag": "a", "splines": [{"points": [[0,0],[0,0],[0,0],[0,0]]}]}]})"),
              HasSubstr("key 'elements[0].splines[0].points': all control points are at (0, 0)"));
  EXPECT_THAT(error_of(R"({"name": "n", "kind": "hedge", "scale_m": 1e400, "seed_tag": "a"})"),
              HasSubstr("bad.json: not valid JSON"));
  EXPECT_THAT(error_of(R"({"kind": "wall"})"), HasSubstr("key '': missing 'name'"));
}

TEST(Element, MissingFileIsOneErrorNamingIt) {
  EXPECT_THAT(
      [] {
        try {
          read_element_set("/nonexistent/hedge.json");
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      HasSubstr("/nonexistent/hedge.json"));
}

}  // namespace
}  // namespace tw
