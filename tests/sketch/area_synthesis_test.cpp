#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "raster/avoidance.hpp"
#include "raster/rasterize.hpp"
#include "sketch/area_synthesis.hpp"
#include "sketch_builders.hpp"

namespace tw {
namespace {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgLine = bg::model::linestring<BgPoint>;
using BgPolygon = bg::model::polygon<BgPoint>;

// A 300 m x 160 m rectangle turned by 20 degrees around (1000, 2000).
Polygon field() {
  const double a = 20.0 * std::numbers::pi / 180.0;
  const Vec2 u{std::cos(a), std::sin(a)}, v = perp(u), c{1000.0, 2000.0};
  return {{c - u * 150.0 - v * 80.0, c + u * 150.0 - v * 80.0, c + u * 150.0 + v * 80.0,
           c - u * 150.0 + v * 80.0}};
}

// Simplified within 1e-9 m: the densified straight wires shrink to a few points, so the
// pairwise distances below stay fast and exact to 1e-9.
BgLine to_bg(const std::vector<Vec2>& line) {
  BgLine dense, out;
  for (Vec2 p : line) dense.emplace_back(p.x, p.y);
  bg::simplify(dense, out, 1e-9);
  return out;
}

BgPolygon to_bg(const Polygon& polygon) {
  BgPolygon out;
  for (Vec2 p : polygon.front()) out.outer().emplace_back(p.x, p.y);
  bg::correct(out);
  return out;
}

// Vine rows: posts (bounded dots) every 0.1 along rows 0.2 apart, each row with its wire (an
// unbounded line just beside the posts).
Sketch vineyard() {
  Sketch sketch;
  sketch.source = "vineyard";
  for (int row = 0; row < 5; ++row) {
    const double y = 0.1 + 0.2 * row;
    sketch.strokes.push_back(
        test::line_stroke({0.0, y + 0.03}, {1.0, y + 0.03}, true, 0.01, "wire"));
    for (int k = 0; k < 10; ++k) {
      sketch.strokes.push_back(test::dot_stroke({0.05 + 0.1 * k, y}, 0.012, "post"));
    }
  }
  return sketch;
}

void expect_disjoint_where_sketch_was(const AreaPattern& p) {
  // Sweep over strokes sorted by their left edge: only neighbours in x can meet.
  struct Item {
    double x0, x1;
    std::size_t index;
  };
  std::vector<Item> items;
  double widest = 0.0;
  for (std::size_t i = 0; i < p.strokes.size(); ++i) {
    double x0 = INFINITY, x1 = -INFINITY;
    for (Vec2 q : p.strokes[i].points) x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
    items.push_back({x0, x1, i});
    widest = std::max(widest, p.strokes[i].width);
  }
  std::sort(items.begin(), items.end(), [](auto& a, auto& b) { return a.x0 < b.x0; });
  for (std::size_t i = 0; i < items.size(); ++i) {
    for (std::size_t j = i + 1; j < items.size() && items[j].x0 <= items[i].x1 + widest; ++j) {
      const PlacedStroke &a = p.strokes[items[i].index], &b = p.strokes[items[j].index];
      if (a.instance == b.instance) continue;
      const double d = bg::distance(to_bg(a.points), to_bg(b.points));
      // Shapes of these sketches never overlap each other there, so they never may here (H3).
      ASSERT_GT(d, 0.5 * (a.width + b.width) - 1e-9)
          << "instances " << a.instance << " (shape " << p.instances[a.instance].shape << ") and "
          << b.instance << " (shape " << p.instances[b.instance].shape << ")";
    }
  }
}

TEST(AreaSynthesis, RepeatsRowsOverTheFieldWithoutOverlapOrLeavingIt) {
  const SupportHierarchy h = analyze_sketch(vineyard());
  AreaSynthesisParams params;
  params.scale = 40.0;  // the sketch covers 40 m x 40 m; the field is 300 m x 160 m
  params.bearing = 20.0 * std::numbers::pi / 180.0;
  params.seed = 7;
  const Polygon domain = field();
  const AreaPattern p = synthesize_area(h, domain, params);
  const BgPolygon region = to_bg(domain);
  int posts = 0, wires = 0;
  for (const ShapeInstance& i : p.instances) (i.unbounded ? wires : posts) += 1;
  // Posts every 4 m along rows 8 m apart over 48 000 m^2, less the margins: on the order of
  // 1500, far beyond the sketch's 50.
  EXPECT_GT(posts, 900);
  EXPECT_LT(posts, 1600);
  // Rows repeated across the field: 160 m / 8 m = 20 wires, give or take the random gaps.
  EXPECT_GE(wires, 16);
  EXPECT_LE(wires, 24);
  for (const PlacedStroke& s : p.strokes) {
    for (Vec2 q : s.points) {
      // Clipped ends lie on the boundary, up to rounding.
      ASSERT_LT(bg::distance(BgPoint(q.x, q.y), region), 1e-6) << q.x << " " << q.y;
    }
  }
  expect_disjoint_where_sketch_was(p);
  // Wires run the whole length of the field in its frame: the longest is close to 300 m.
  double longest = 0.0;
  for (const PlacedStroke& s : p.strokes) {
    if (p.instances[s.instance].unbounded)
      longest = std::max(longest, double(bg::length(to_bg(s.points))));
  }
  EXPECT_GT(longest, 280.0);
  EXPECT_LT(longest, 301.0);
}

// A lead field of circles about a point south of the field (a cone's contours): the wires
// curve with it. At every placed segment their direction is the circle's tangent there, and
// each keeps its distance to the centre; laid straight, the field's ends would be off by
// about 40 degrees. H3 still holds.
TEST(AreaSynthesis, RowsCurveWithTheLeadField) {
  const SupportHierarchy h = analyze_sketch(vineyard());
  const Vec2 apex{1000.0, 1800.0};
  AreaSynthesisParams params;
  params.scale = 40.0;
  params.seed = 7;
  params.lead_field = [&](Vec2 p) -> std::optional<double> {
    return std::atan2(p.y - apex.y, p.x - apex.x) + 0.5 * std::numbers::pi;
  };
  params.bearing = *params.lead_field({1000.0, 2000.0});
  const Polygon domain = field();
  const AreaPattern p = synthesize_area(h, domain, params);
  int wires = 0;
  double worst_turn = 0.0, worst_spread = 0.0, widest_span = 0.0;
  for (const PlacedStroke& s : p.strokes) {
    if (!p.instances[s.instance].unbounded) continue;
    ++wires;
    double r0 = INFINITY, r1 = -INFINITY, a0 = INFINITY, a1 = -INFINITY;
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
      const Vec2 d = s.points[i + 1] - s.points[i];
      const Vec2 mid = (s.points[i] + s.points[i + 1]) * 0.5;
      r0 = std::min(r0, distance(mid, apex)), r1 = std::max(r1, distance(mid, apex));
      const double bearing = std::atan2(mid.y - apex.y, mid.x - apex.x);
      a0 = std::min(a0, bearing), a1 = std::max(a1, bearing);
      if (length(d) < 0.5) continue;  // a clipped end's sliver
      const Vec2 tangent = perp(normalized(mid - apex));
      worst_turn =
          std::max(worst_turn, std::asin(std::min(1.0, std::abs(cross(normalized(d), tangent)))));
    }
    worst_spread = std::max(worst_spread, r1 - r0);
    widest_span = std::max(widest_span, a1 - a0);
  }
  EXPECT_GE(wires, 12);
  EXPECT_LT(worst_turn * 180.0 / std::numbers::pi, 2.0);
  EXPECT_LT(worst_spread, 1.0);  // a wire is a circle about the apex, to a metre
  EXPECT_GT(widest_span * 180.0 / std::numbers::pi, 60.0);  // and it does bend
  expect_disjoint_where_sketch_was(p);
  for (const PlacedStroke& s : p.strokes)
    for (Vec2 q : s.points) ASSERT_LT(bg::distance(BgPoint(q.x, q.y), to_bg(domain)), 1e-6);
}

TEST(AreaSynthesis, KeepsTheSketchAsDrawnAtTheCentroid) {
  const SupportHierarchy h = analyze_sketch(test::staggered_dots());
  AreaSynthesisParams params;
  params.scale = 50.0;
  const Polygon domain = {{{-200, -200}, {200, -200}, {200, 200}, {-200, 200}}};
  const AreaPattern p = synthesize_area(h, domain, params);
  // Every sketch dot has an instance exactly where the sketch puts it (centroid = sketch centre).
  for (const SketchShape& shape : h.shapes) {
    const Vec2 expected = (shape.box.center - Vec2{0.5, 0.5}) * 50.0;
    bool found = false;
    for (const ShapeInstance& i : p.instances)
      found = found || distance(i.position, expected) < 1e-9;
    EXPECT_TRUE(found) << expected.x << " " << expected.y;
  }
  expect_disjoint_where_sketch_was(p);
}

TEST(AreaSynthesis, ASingleWaveIsExtendedButNotRepeated) {
  const SupportHierarchy h = analyze_sketch(test::single_wave());
  AreaSynthesisParams params;
  params.scale = 20.0;
  const Polygon domain = {{{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}};
  const AreaPattern p = synthesize_area(h, domain, params);
  ASSERT_EQ(p.instances.size(), 1u);  // H2: it appears once in the sketch
  ASSERT_EQ(p.strokes.size(), 1u);
  // Extended across the whole 200 m square by mirror duplication, staying a wave of the
  // sketch's amplitude (0.1 x 20 m = 2 m).
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (Vec2 q : p.strokes[0].points) {
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  EXPECT_NEAR(x0, -100.0, 1.0);
  EXPECT_NEAR(x1, 100.0, 1.0);
  EXPECT_NEAR(y1 - y0, 4.0, 0.3);
}

TEST(AreaSynthesis, NothingTouchesAForbiddenPixel) {
  const SupportHierarchy h = analyze_sketch(vineyard());
  const Polygon domain = field();
  GridSpec grid;
  grid.width = 400, grid.height = 300;
  grid.origin_x = 800.0, grid.origin_y = 2150.0;
  grid.pixel_width = grid.pixel_height = 1.0;
  AvoidanceInputs inputs;
  inputs.lines = {{{800.0, 1900.0}, {1200.0, 2100.0}}};  // a road across the field
  inputs.line_widths = {12.0};
  const AvoidanceMap map = build_avoidance_map(inputs, grid, Window::whole(grid));
  const SparseAvoidance avoidance{grid, sparse_from_dense(map.forbidden, std::uint8_t(0), 64)};
  AreaSynthesisParams params;
  params.scale = 40.0;
  params.bearing = 20.0 * std::numbers::pi / 180.0;
  const AreaPattern p = synthesize_area(h, domain, params, &avoidance);
  EXPECT_GT(p.forbidden, 0);
  std::vector<std::vector<Vec2>> lines;
  std::vector<double> widths;
  for (const PlacedStroke& s : p.strokes) lines.push_back(s.points), widths.push_back(s.width);
  Raster<std::uint8_t> drawn;
  burn_buffered_lines(lines, widths, grid, Window::whole(grid), drawn, 1);
  int touching = 0, drawn_pixels = 0;
  for (std::size_t i = 0; i < drawn.pixels.size(); ++i) {
    drawn_pixels += drawn.pixels[i];
    touching += drawn.pixels[i] && map.forbidden.pixels[i];
  }
  EXPECT_GT(drawn_pixels, 1000);
  EXPECT_EQ(touching, 0);
}

// Straight wires cut by the road are written as straight runs: two points each, however fine
// the avoidance lattice (1 m here, where every half cell used to be a vertex).
TEST(AreaSynthesis, StraightRunsAreTwoPointsWhereverTheyAreCut) {
  const SupportHierarchy h = analyze_sketch(vineyard());
  GridSpec grid;
  grid.width = 400, grid.height = 300;
  grid.origin_x = 800.0, grid.origin_y = 2150.0;
  AvoidanceInputs inputs;
  inputs.lines = {{{800.0, 1900.0}, {1200.0, 2100.0}}};
  inputs.line_widths = {12.0};
  const AvoidanceMap map = build_avoidance_map(inputs, grid, Window::whole(grid));
  const SparseAvoidance avoidance{grid, sparse_from_dense(map.forbidden, std::uint8_t(0), 64)};
  AreaSynthesisParams params;
  params.scale = 40.0;
  params.bearing = 20.0 * std::numbers::pi / 180.0;
  const AreaPattern p = synthesize_area(h, field(), params, &avoidance);
  int wires = 0, cut = 0;
  for (const PlacedStroke& s : p.strokes) {
    if (!p.instances[std::size_t(s.instance)].unbounded) continue;
    ++wires;
    ASSERT_EQ(s.points.size(), 2u);
    cut += distance(s.points.front(), s.points.back()) < 280.0;
  }
  EXPECT_GE(wires, 20);
  EXPECT_GT(cut, 10);  // the road cuts them: two runs each
}

// Unbounded curves (a wave laid along a cone's contours) are written within the tolerance of
// the densely traced stroke, both ways (Hausdorff), with vertices at least a few metres apart.
TEST(AreaSynthesis, CurvedStrokesAreSimplifiedWithinTheTolerance) {
  const SupportHierarchy h = analyze_sketch(test::single_wave());
  const Vec2 apex{0.0, -400.0};
  AreaSynthesisParams params;
  params.scale = 20.0;
  params.lead_field = [&](Vec2 p) -> std::optional<double> {
    return std::atan2(p.y - apex.y, p.x - apex.x) + 0.5 * std::numbers::pi;
  };
  params.bearing = *params.lead_field({0.0, 0.0});
  const Polygon domain = {{{-150, -100}, {150, -100}, {150, 100}, {-150, 100}}};
  params.tolerance = 1e-9;
  const AreaPattern dense = synthesize_area(h, domain, params);
  params.tolerance = 0.25;
  const AreaPattern simple = synthesize_area(h, domain, params);
  ASSERT_EQ(dense.strokes.size(), 1u);
  ASSERT_EQ(simple.strokes.size(), 1u);
  const BgLine a = to_bg(dense.strokes[0].points), b = to_bg(simple.strokes[0].points);
  double hausdorff = 0.0;
  for (const BgPoint& p : a) hausdorff = std::max(hausdorff, double(bg::distance(p, b)));
  for (const BgPoint& p : b) hausdorff = std::max(hausdorff, double(bg::distance(p, a)));
  EXPECT_LE(hausdorff, 0.25 + 1e-9);
  const double length = bg::length(b);
  EXPECT_GT(length, 290.0);
  EXPECT_LT(double(simple.strokes[0].points.size()), 0.5 * double(dense.strokes[0].points.size()));
  EXPECT_GT(length / double(simple.strokes[0].points.size() - 1), 2.0);
}

TEST(AreaSynthesis, DeterministicWithTheSeed) {
  const SupportHierarchy h = analyze_sketch(vineyard());
  AreaSynthesisParams params;
  params.scale = 40.0;
  params.seed = 3;
  const AreaPattern a = synthesize_area(h, field(), params);
  const AreaPattern b = synthesize_area(h, field(), params);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t i = 0; i < a.strokes.size(); ++i)
    EXPECT_EQ(a.strokes[i].points, b.strokes[i].points);
  params.seed = 4;
  const AreaPattern c = synthesize_area(h, field(), params);
  bool differs = c.strokes.size() != a.strokes.size();
  for (std::size_t i = 0; !differs && i < a.strokes.size(); ++i)
    differs = a.strokes[i].points != c.strokes[i].points;
  EXPECT_TRUE(differs);
}

TEST(AreaSynthesis, HybridKeepsTheRowsAndTakesTheShapes) {
  const SupportHierarchy rows = analyze_sketch(test::staggered_dots());
  Sketch trees;
  trees.source = "trees";
  for (double x : {0.2, 0.5, 0.8}) {
    trees.strokes.push_back(test::line_stroke({x, 0.4}, {x, 0.5}, false, 0.01, "trunk"));
    trees.strokes.push_back(test::dot_stroke({x, 0.55}, 0.05, "crown"));
  }
  const SupportHierarchy donor = analyze_sketch(trees);
  const SupportHierarchy hybrid = hybridize(rows, donor);
  EXPECT_EQ(hybrid.shapes.size(), rows.shapes.size());
  for (const SketchShape& s : hybrid.shapes) EXPECT_EQ(s.strokes.size(), 2u);  // trunk + crown
  EXPECT_EQ(hybrid.fibres.size(), rows.fibres.size());
  ASSERT_EQ(hybrid.leads.size(), 1u);
  EXPECT_EQ(hybrid.leads[0].members.size(), rows.leads[0].members.size());
}

TEST(AreaSynthesis, LongAxisAndBadParameters) {
  EXPECT_NEAR(long_axis_bearing(field()), 20.0 * std::numbers::pi / 180.0, 1e-6);
  const SupportHierarchy h = analyze_sketch(test::single_wave());
  AreaSynthesisParams params;
  params.scale = 0.0;
  EXPECT_THROW(synthesize_area(h, field(), params), Error);
  params.scale = 1.0;
  EXPECT_THROW(synthesize_area(h, Polygon{}, params), Error);
}

}  // namespace
}  // namespace tw
