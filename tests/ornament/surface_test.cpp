#include "ornament/surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/error.hpp"

namespace tw {
namespace {

GridSpec test_grid(int n) {
  return {n, n, 1000.0, 2000.0, 2.0, 2.0};
}

TerrainSurface surface_of(int n, const std::function<double(Vec2)>& z) {
  const GridSpec grid = test_grid(n);
  Raster<float> h(n, n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) h.at(c, r) = float(z(grid.pixel_centre_world(c, r)));
  }
  return TerrainSurface(h, grid, Window::whole(grid));
}

struct P3 {
  double x, y, z;
};
P3 lift(const TerrainSurface& s, const SurfacePoint& p) {
  const Vec2 w = s.world(p);
  return {w.x, w.y, s.height(p)};
}
double dist3(P3 a, P3 b) {
  return std::sqrt(std::pow(a.x - b.x, 2) + std::pow(a.y - b.y, 2) + std::pow(a.z - b.z, 2));
}

TEST(Surface, LocateWorldAndHeightRoundTrip) {
  const TerrainSurface s = surface_of(8, [](Vec2 w) { return 0.25 * (w.x - 1000) + 3.0; });
  EXPECT_EQ(s.vertex_count(), 64);
  EXPECT_EQ(s.face_count(), 98);
  const auto p = s.locate({1005.3, 1993.1});
  ASSERT_TRUE(p);
  EXPECT_NEAR(s.world(*p).x, 1005.3, 1e-9);
  EXPECT_NEAR(s.world(*p).y, 1993.1, 1e-9);
  EXPECT_NEAR(s.height(*p), 0.25 * 5.3 + 3.0, 1e-5);  // a plane: exact up to float heights
  EXPECT_EQ(s.pixel_of(*p), (std::pair<int, int>{2, 3}));
  EXPECT_FALSE(s.locate({1000.5, 1999.0}));  // before the first pixel centre
  EXPECT_THROW(TerrainSurface(Raster<float>(3, 3), test_grid(4), Window::whole(test_grid(4))),
               Error);
}

TEST(Surface, StraightestGeodesicOnAPlaneIsTheStraightLine) {
  const TerrainSurface flat = surface_of(64, [](Vec2) { return 10.0; });
  const SurfaceFrame frame{*flat.locate({1040.3, 1930.7}), normalized(Vec2{3, 4})};
  const auto walk = flat.straightest_geodesic(frame, {30.0, 17.0});
  ASSERT_TRUE(walk);
  // heading (0.6, 0.8); left axis (-0.8, 0.6): 30 * (0.6, 0.8) + 17 * (-0.8, 0.6)
  EXPECT_NEAR(flat.world(walk->end).x, 1040.3 + 18.0 - 13.6, 1e-9);
  EXPECT_NEAR(flat.world(walk->end).y, 1930.7 + 24.0 + 10.2, 1e-9);
  EXPECT_NEAR(walk->heading.x, normalized(Vec2{18.0 - 13.6, 24.0 + 10.2}).x, 1e-12);
  EXPECT_FALSE(flat.straightest_geodesic(frame, {500.0, 0.0}));  // leaves the window
}

TEST(Surface, StraightestGeodesicOnAnInclinedPlaneKeepsItsLength) {
  const TerrainSurface tilted =
      surface_of(64, [](Vec2 w) { return 0.5 * (w.x - 1000) + 0.2 * (w.y - 2000); });
  const SurfaceFrame frame{*tilted.locate({1020.0, 1910.0}), normalized(Vec2{1, 1})};
  const auto walk = tilted.straightest_geodesic(frame, {25.0, 35.0});
  ASSERT_TRUE(walk);
  // On a plane the geodesic is the 3-D straight segment: its chord is its length.
  EXPECT_NEAR(dist3(lift(tilted, frame.origin), lift(tilted, walk->end)), std::hypot(25.0, 35.0),
              1e-4);
  // The contour of z = 0.5 x + 0.2 y runs along (-0.2, 0.5).
  const Vec2 contour = tilted.contour_direction(frame.origin);
  EXPECT_NEAR(contour.x, normalized(Vec2{-0.2, 0.5}).x, 1e-6);
  EXPECT_NEAR(contour.y, normalized(Vec2{-0.2, 0.5}).y, 1e-6);
}

TEST(Surface, GeodesicMidpointLiesHalfwayOnTheExactShortestPath) {
  // Rolling hills: the midpoint found by shooting straightest geodesics lies on CGAL's exact
  // shortest path (the two halves add up to it) and close to its middle. Straightest and
  // shortest geodesics differ on a polyhedron (Polthier & Schmies), hence the looser 3 %.
  const TerrainSurface hills = surface_of(24, [](Vec2 w) {
    return 2.5 * std::sin((w.x - 1000) / 9.0) * std::cos((w.y - 2000) / 11.0);
  });
  const SurfacePoint a = *hills.locate({1006.0, 1994.0}), b = *hills.locate({1035.0, 1962.5});
  const auto m = hills.geodesic_lerp(a, b, 0.5);
  ASSERT_TRUE(m);
  const double whole = hills.shortest_path_length(a, b);
  EXPECT_GT(whole, std::hypot(29.0, 31.5));  // longer than the map distance
  const double first = hills.shortest_path_length(a, *m),
               second = hills.shortest_path_length(*m, b);
  EXPECT_NEAR(first + second, whole, 0.002 * whole);
  EXPECT_NEAR(first, whole / 2, 0.03 * whole);
  EXPECT_NEAR(second, whole / 2, 0.03 * whole);
  EXPECT_EQ(*hills.geodesic_lerp(a, b, 0.0), a);
}

TEST(Surface, HeatDistancesApproximateTheGeodesicDistance) {
  const TerrainSurface flat = surface_of(48, [](Vec2) { return 0.0; });
  const SurfacePoint source = flat.vertex_point(10 * 48 + 10);
  const std::vector<double> d = flat.heat_distances({source});
  ASSERT_EQ(d.size(), 48u * 48u);
  EXPECT_NEAR(d[10 * 48 + 10], 0.0, 0.5);
  const double far = std::hypot(30.0 * 2, 25.0 * 2);  // vertex (40, 35)
  EXPECT_NEAR(d[35 * 48 + 40], far, 0.05 * far);
  EXPECT_NEAR(flat.interpolate(d, flat.vertex_point(35 * 48 + 40)), d[35 * 48 + 40], 1e-9);
  const std::vector<double> none = flat.heat_distances({});
  EXPECT_TRUE(std::isinf(none[0]));
}

TEST(Surface, HeatDistancesOnAPartMatchTheWholeMeshWellInsideIt) {
  // Rolling hills, a short line of sources in the middle of a 40 x 30 part of a 96 x 96 mesh:
  // the part's distances agree with the whole mesh's wherever the part reaches 1.2 times the
  // distance beyond the vertex (what the growth's local update relies on), and are +inf
  // nowhere inside it.
  const int n = 96;
  const TerrainSurface hills = surface_of(n, [](Vec2 w) {
    return 0.2 * (w.y - 2000) + 4.0 * std::sin((w.x - 1000) / 17.0) * std::cos((w.y - 2000) / 23.0);
  });
  std::vector<SurfacePoint> sources;
  for (int i = 44; i <= 52; ++i) sources.push_back(hills.vertex_point(48 * n + i));
  const Window part{30, 33, 40, 30};
  const std::vector<double> whole = hills.heat_distances(sources);
  const std::vector<double> local = hills.heat_distances(sources, part);
  ASSERT_EQ(local.size(), 40u * 30u);
  int compared = 0;
  for (int j = 0; j < part.height; ++j) {
    for (int i = 0; i < part.width; ++i) {
      const int c = part.col0 + i, r = part.row0 + j;
      const double d = whole[std::size_t(r) * n + c], l = local[std::size_t(j) * part.width + i];
      ASSERT_TRUE(std::isfinite(l));
      // Metres from the vertex to the part's edge, horizontally.
      const double room = 2.0 * std::min({i, j, part.width - 1 - i, part.height - 1 - j});
      if (room < 0.2 * d) continue;
      EXPECT_NEAR(l, d, 0.01 * d + 2.0) << "vertex " << c << "," << r;
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
  EXPECT_NEAR(local[std::size_t(48 - 33) * 40 + (48 - 30)], 0.0, 0.5);
  // No source inside: nothing is reached; a part off the mesh is an error.
  const std::vector<double> empty = hills.heat_distances({hills.vertex_point(0)}, part);
  EXPECT_TRUE(std::isinf(empty[0]));
  EXPECT_THROW(hills.heat_distances(sources, Window{80, 0, 20, 10}), Error);
}

}  // namespace
}  // namespace tw
