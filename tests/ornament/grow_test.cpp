#include "ornament/grow.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "test_support.hpp"

namespace tw {
namespace {

struct World {
  GridSpec grid;
  Raster<float> heights;
  Raster<std::uint8_t> allowed;
};

// A hillside 160 m square at 2 m with rolling bumps; allowed: a disc of radius 70 m minus a
// 6 m-wide road running north-south through x = 1100.
World hillside(const std::function<double(Vec2)>& z) {
  World w;
  const int n = 80;
  w.grid = {n, n, 1000.0, 2000.0, 2.0, 2.0};
  w.heights = Raster<float>(n, n);
  w.allowed = Raster<std::uint8_t>(n, n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const Vec2 p = w.grid.pixel_centre_world(c, r);
      w.heights.at(c, r) = float(z(p));
      const bool in_disc = distance(p, {1080.0, 1920.0}) < 70.0;
      const bool on_road = std::abs(p.x - 1100.0) < 3.0;
      w.allowed.at(c, r) = in_disc && !on_road;
    }
  }
  return w;
}

double rolling(Vec2 p) {
  return 0.15 * (p.y - 1920.0) +
         3.0 * std::sin((p.x - 1000.0) / 23.0) * std::cos((p.y - 2000.0) / 31.0);
}

ElementSet sample(const char* name) {
  return read_element_set(test::source_dir() / "samples/ornaments" / (std::string(name) + ".json"));
}

GrowthResult grow(const World& w, const ElementSet& set, GrowthParams params) {
  const TerrainSurface surface(w.heights, w.grid, Window::whole(w.grid));
  return grow_ornaments(surface, w.allowed, set, params);
}

// Orientation sign of c relative to a->b, in long double (the test's own predicate).
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

TEST(Grow, HedgesFillTheRegionWithoutCrossingsOrForbiddenPixels) {
  const World w = hillside(rolling);
  const ElementSet set = sample("hedge");
  GrowthParams params;
  params.seed = 7;
  const GrowthResult r = grow(w, set, params);
  ASSERT_GE(r.elements, 15);
  EXPECT_GE(r.ornaments, 2);  // the road splits the disc: one ornament cannot cross it
  EXPECT_GT(r.rejected_crossing + r.rejected_forbidden, 0);
  // No two lines cross (they may only meet end to end where one grows from the other).
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    for (std::size_t j = i + 1; j < r.lines.size(); ++j) {
      const auto &p = r.lines[i].points, &q = r.lines[j].points;
      for (std::size_t a = 0; a + 1 < p.size(); ++a) {
        for (std::size_t b = 0; b + 1 < q.size(); ++b) {
          ASSERT_FALSE(segments_cross(p[a], p[a + 1], q[b], q[b + 1]))
              << "lines " << i << " and " << j;
        }
      }
    }
  }
  // None enters a forbidden pixel: dense samples along every segment.
  for (const GrownLine& line : r.lines) {
    for (std::size_t a = 0; a + 1 < line.points.size(); ++a) {
      for (int k = 0; k <= 64; ++k) {
        const Vec2 px = w.grid.world_to_pixel(lerp(line.points[a], line.points[a + 1], k / 64.0));
        ASSERT_TRUE(w.allowed.at(int(px.x), int(px.y)))
            << line.name << " at " << px.x << "," << px.y;
      }
    }
  }
}

TEST(Grow, BestCandidateCoversMoreThanTheGreedyFirstFit) {
  // The paper's Figure 6: over a few ornaments of a branching element, picking the candidate
  // farthest from what is placed covers more than taking the first that fits.
  const World w = hillside(rolling);
  const ElementSet set = sample("ditch");
  const TerrainSurface surface(w.heights, w.grid, Window::whole(w.grid));
  double cover_best = 0.0, cover_greedy = 0.0;
  for (std::uint64_t seed : {1, 2, 3}) {
    GrowthParams best;
    best.seed = seed;
    best.max_ornaments = 3;
    GrowthParams greedy = best;
    greedy.selection = CandidateSelection::first_fit;
    cover_best += ornament_coverage(surface, w.allowed,
                                    grow_ornaments(surface, w.allowed, set, best).lines, 6.0) /
                  3;
    cover_greedy += ornament_coverage(surface, w.allowed,
                                      grow_ornaments(surface, w.allowed, set, greedy).lines, 6.0) /
                    3;
  }
  std::printf("coverage within 6 m (3 ornaments, 3 seeds): best candidate %.3f, first fit %.3f\n",
              cover_best, cover_greedy);
  EXPECT_GT(cover_best, cover_greedy + 0.1);
}

TEST(Grow, SameSeedSameLinesBitForBit) {
  const World w = hillside(rolling);
  const ElementSet set = sample("ditch");
  GrowthParams params;
  params.seed = 3;
  params.max_ornaments = 4;
  const GrowthResult a = grow(w, set, params), b = grow(w, set, params);
  ASSERT_EQ(a.lines.size(), b.lines.size());
  for (std::size_t i = 0; i < a.lines.size(); ++i) {
    EXPECT_EQ(a.lines[i].points, b.lines[i].points);
    EXPECT_EQ(a.lines[i].heights, b.lines[i].heights);
  }
  params.seed = 4;
  const GrowthResult c = grow(w, set, params);
  EXPECT_NE(c.lines.front().points, a.lines.front().points);
}

TEST(Grow, LocalDistanceUpdatesKeepTheWholeMeshsCoverage) {
  // Each placed element's distances solved on the part of the mesh they can change (local
  // once the region has filled, whole while an ornament runs into open ground): the growth
  // covers the region as the whole-mesh reference does (the placements may differ through
  // the heat method's last digits near the part's edge).
  const World w = hillside(rolling);
  const TerrainSurface surface(w.heights, w.grid, Window::whole(w.grid));
  for (const char* name : {"hedge", "ditch"}) {
    const ElementSet set = sample(name);
    GrowthParams local;
    local.seed = 5;
    GrowthParams whole = local;
    whole.local_distances = false;
    const GrowthResult a = grow_ornaments(surface, w.allowed, set, local);
    const GrowthResult b = grow_ornaments(surface, w.allowed, set, whole);
    EXPECT_EQ(b.local_solves, 0);
    EXPECT_EQ(b.whole_solves, b.elements);
    EXPECT_EQ(a.local_solves + a.whole_solves, a.elements);
    EXPECT_GT(a.local_solves, 0) << name;
    const double cover_a = ornament_coverage(surface, w.allowed, a.lines, set.scale_m / 2);
    const double cover_b = ornament_coverage(surface, w.allowed, b.lines, set.scale_m / 2);
    std::printf(
        "%s: local %d elements (%d local, %d whole solves) coverage %.3f; whole %d "
        "elements coverage %.3f\n",
        name, a.elements, a.local_solves, a.whole_solves, cover_a, b.elements, cover_b);
    EXPECT_NEAR(cover_a, cover_b, 0.05) << name;
    EXPECT_NEAR(a.elements, b.elements, 0.15 * b.elements + 2) << name;
  }
}

TEST(Grow, ContourAlignmentKeepsTerraceWallsLevel) {
  const World w = hillside([](Vec2 p) { return 0.3 * (p.y - 1920.0); });
  const ElementSet set = sample("wall");
  const auto mean_slope = [&](OrnamentAlignment alignment) {
    GrowthParams params;
    params.seed = 5;
    params.alignment = alignment;
    const GrowthResult r = grow(w, set, params);
    double rise = 0.0, run = 0.0;
    for (const GrownLine& line : r.lines) {
      for (std::size_t k = 0; k + 1 < line.points.size(); ++k) {
        rise += std::abs(line.heights[k + 1] - line.heights[k]);
        run += distance(line.points[k], line.points[k + 1]);
      }
    }
    return rise / run;
  };
  const double contour = mean_slope(OrnamentAlignment::contour);
  const double growth = mean_slope(OrnamentAlignment::growth);
  std::printf("mean |slope| along walls: contour-aligned %.3f, growth-aligned %.3f\n", contour,
              growth);
  EXPECT_LT(contour, 0.5 * growth);
}

TEST(Grow, EntersForbiddenFollowsEveryPixelOfTheSegment) {
  const GridSpec grid{10, 10, 0.0, 10.0, 1.0, 1.0};
  Raster<std::uint8_t> allowed(10, 10, 1);
  allowed.at(5, 5) = 0;
  // Clips only the corner of pixel (5, 5): world (5.9, 4.95) lies inside it.
  EXPECT_TRUE(enters_forbidden(grid, Window::whole(grid), allowed, {5.5, 3.5}, {6.5, 5.3}));
  EXPECT_FALSE(enters_forbidden(grid, Window::whole(grid), allowed, {6.05, 3.5}, {6.5, 5.3}));
  EXPECT_TRUE(enters_forbidden(grid, Window::whole(grid), allowed, {1.0, 1.0}, {-0.5, 1.0}));
}

}  // namespace
}  // namespace tw
