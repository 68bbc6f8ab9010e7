#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "core/error.hpp"
#include "sketch/hierarchy.hpp"
#include "sketch_builders.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::dot_stroke;
using test::line_stroke;

TEST(SketchAnalysis, TwoFamiliesOfParallelLinesGiveTwoLeadDirections) {
  const SupportHierarchy h = analyze_sketch(test::two_families());
  ASSERT_EQ(h.shapes.size(), 7u);
  for (std::size_t i = 0; i < h.shapes.size(); ++i) {
    EXPECT_EQ(h.shapes[i].support, ShapeSupport::fibre);
    // The horizontal lines reach both borders; the slanted ones neither.
    EXPECT_EQ(h.shapes[i].category, i < 4 ? UnboundedCategory::line : UnboundedCategory::ray);
  }
  ASSERT_EQ(h.fibres.size(), 7u);
  EXPECT_EQ(h.medians.size(), 7u);  // 0.2 apart, far beyond the perceived-distance threshold
  ASSERT_EQ(h.leads.size(), 2u);
  std::vector<std::size_t> sizes{h.leads[0].members.size(), h.leads[1].members.size()};
  std::vector<double> angles{line_angle(h.leads[0].line.direction),
                             line_angle(h.leads[1].line.direction)};
  if (sizes[0] < sizes[1]) std::swap(sizes[0], sizes[1]), std::swap(angles[0], angles[1]);
  EXPECT_EQ(sizes[0], 4u);
  EXPECT_EQ(sizes[1], 3u);
  EXPECT_NEAR(std::min(angles[0], std::numbers::pi - angles[0]), 0.0, 1e-9);
  EXPECT_NEAR(angles[1], std::numbers::pi / 3, 1e-9);
  // Horizontal lines 0.2 apart, 0.01 thick: gaps of 0.19 between them, and the torus's wrap
  // from y = 0.8 to 1.2 leaves 0.39.
  const Grouping& horizontal = h.leads[0].members.size() == 4 ? h.leads[0] : h.leads[1];
  EXPECT_NEAR(horizontal.gap_min, 0.19, 1e-9);
  EXPECT_NEAR(horizontal.gap_max, 0.39, 1e-9);
}

TEST(SketchAnalysis, StaggeredDotsLineUpInRows) {
  const SupportHierarchy h = analyze_sketch(test::staggered_dots());
  ASSERT_EQ(h.shapes.size(), test::staggered_dots().strokes.size());
  for (const SketchShape& s : h.shapes) EXPECT_EQ(s.support, ShapeSupport::point);
  ASSERT_EQ(h.fibres.size(), 5u);
  for (const Fibre& f : h.fibres) {
    EXPECT_FALSE(f.unbounded);
    EXPECT_NEAR(std::sin(line_angle(f.line.direction)), 0.0, 1e-6);  // rows run along x
    EXPECT_GE(f.shapes.size(), 8u);
    // Dots of radius 0.015 (plus half their stroke) every 0.1: gaps of 0.066 along the row.
    for (std::size_t k = 0; k + 1 < f.gaps_along.size(); ++k) {
      EXPECT_NEAR(f.gaps_along[k], 0.1 - 2 * 0.017, 1e-3);
    }
  }
  EXPECT_EQ(h.medians.size(), 5u);
  ASSERT_EQ(h.leads.size(), 1u);
  EXPECT_EQ(h.leads[0].members.size(), 5u);
  EXPECT_NEAR(h.leads[0].gap_min, 0.2 - 2 * 0.017, 1e-3);
}

TEST(SketchAnalysis, TouchingStrokesFormOneShapeAndDashesOneSegmentFibre) {
  Sketch sketch;
  sketch.source = "test";
  // A tree: trunk and crown touching; another tree far away.
  for (double x : {0.2, 0.7}) {
    sketch.strokes.push_back(line_stroke({x, 0.1}, {x, 0.2}, false, 0.01, "trunk"));
    sketch.strokes.push_back(dot_stroke({x, 0.25}, 0.05, "crown"));
  }
  // Dashes along y = 0.6: bounded and anisotropic, collinear.
  for (double x : {0.1, 0.35, 0.6, 0.85}) {
    sketch.strokes.push_back(line_stroke({x, 0.6}, {x + 0.1, 0.6}, false, 0.01, "dash"));
  }
  const SupportHierarchy h = analyze_sketch(sketch);
  ASSERT_EQ(h.shapes.size(), 6u);
  EXPECT_EQ(h.shapes[0].strokes, (std::vector<int>{0, 1}));
  EXPECT_EQ(h.shapes[1].strokes, (std::vector<int>{2, 3}));
  int segments = 0;
  for (const SketchShape& s : h.shapes) segments += s.support == ShapeSupport::segment;
  EXPECT_EQ(segments, 4);
  int dash_fibres = 0;
  for (const Fibre& f : h.fibres) {
    if (f.shapes.size() == 4) {
      ++dash_fibres;
      EXPECT_NEAR(f.line.point.y, 0.6, 1e-9);
      EXPECT_NEAR(f.gaps_along.front(), 0.15 - 0.01, 1e-9);
    }
  }
  EXPECT_EQ(dash_fibres, 1);
}

TEST(SketchAnalysis, SingleWaveIsOneCurveFibreNotRepeated) {
  const SupportHierarchy h = analyze_sketch(test::single_wave());
  ASSERT_EQ(h.shapes.size(), 1u);
  EXPECT_EQ(h.shapes[0].category, UnboundedCategory::curve);
  ASSERT_EQ(h.leads.size(), 1u);
  EXPECT_EQ(h.leads[0].members.size(), 1u);
  EXPECT_EQ(h.leads[0].gap_max, 0.0);
}

TEST(SketchAnalysis, PerceivedDistanceFollowsPositionAndOrientation) {
  const SupportLine a{{0.5, 0.2}, {1.0, 0.0}}, b{{0.5, 0.3}, {1.0, 0.0}};
  EXPECT_NEAR(perceived_distance(a, b), 0.1, 1e-12);
  // Fig. 3: a nearly parallel close line is nearer than a crossing steep one.
  const SupportLine c{{0.5, 0.25}, normalized({1.0, 0.05})};
  const SupportLine d{{0.5, 0.25}, normalized({1.0, 1.0})};
  EXPECT_LT(perceived_distance(a, c), perceived_distance(a, d));
  // A vertical and a horizontal line share no border line they both cross.
  EXPECT_TRUE(std::isinf(perceived_distance(a, {{0.5, 0.5}, {0.0, 1.0}})));
}

TEST(SketchLoad, ReadsGeoJsonStrokesAndNamesTheBadFid) {
  test::TempDir dir;
  {
    std::ofstream out(dir / "sketch.geojson");
    out << R"({"type":"FeatureCollection","features":[
      {"type":"Feature","id":1,"properties":{"type":"unbounded","material":"wire","thickness":0.02},
       "geometry":{"type":"LineString","coordinates":[[0,0.5],[1,0.5]]}},
      {"type":"Feature","id":2,"properties":{},
       "geometry":{"type":"LineString","coordinates":[[0.2,0.2],[0.3,0.3]]}}]})";
  }
  const Sketch sketch = load_sketch(dir / "sketch.geojson");
  ASSERT_EQ(sketch.strokes.size(), 2u);
  EXPECT_TRUE(sketch.strokes[0].unbounded);
  EXPECT_EQ(sketch.strokes[0].material, "wire");
  EXPECT_DOUBLE_EQ(sketch.strokes[0].thickness, 0.02);
  EXPECT_FALSE(sketch.strokes[1].unbounded);
  EXPECT_EQ(sketch.strokes[1].material, "shape");
  {
    std::ofstream out(dir / "bad.geojson");
    out << R"({"type":"FeatureCollection","features":[
      {"type":"Feature","id":7,"properties":{},
       "geometry":{"type":"LineString","coordinates":[[0.2,0.2],[1.3,0.3]]}}]})";
  }
  try {
    load_sketch(dir / "bad.geojson");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("FID 7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside the input space"), std::string::npos);
  }
}

TEST(SketchLoad, AThicknessThatIsNotANumberNamesTheFidAndTheText) {
  test::TempDir dir;
  {
    std::ofstream out(dir / "text.geojson");
    out << R"({"type":"FeatureCollection","features":[
      {"type":"Feature","id":4,"properties":{"thickness":"0.03"},
       "geometry":{"type":"LineString","coordinates":[[0.1,0.5],[0.9,0.5]]}},
      {"type":"Feature","id":5,"properties":{"thickness":"abc"},
       "geometry":{"type":"LineString","coordinates":[[0.2,0.2],[0.3,0.3]]}}]})";
  }
  try {
    load_sketch(dir / "text.geojson");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("FID 5"), std::string::npos) << message;
    EXPECT_NE(message.find("thickness must be a number"), std::string::npos) << message;
    EXPECT_NE(message.find("'abc'"), std::string::npos) << message;
  }
  {
    std::ofstream out(dir / "text.geojson");
    out << R"({"type":"FeatureCollection","features":[
      {"type":"Feature","id":4,"properties":{"thickness":"0.03"},
       "geometry":{"type":"LineString","coordinates":[[0.1,0.5],[0.9,0.5]]}}]})";
  }
  EXPECT_DOUBLE_EQ(load_sketch(dir / "text.geojson").strokes[0].thickness, 0.03);
}

}  // namespace
}  // namespace tw
