#pragma once
// Deterministic test shapes in a UTM-like projected frame.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "raster/polygon.hpp"

namespace tw::test {

// A star-shaped ring around `centre` with `vertices` points and radii in [r_min, r_max].
inline Ring random_star(std::mt19937& rng, Vec2 centre, double r_min, double r_max, int vertices,
                        bool clockwise = false) {
  std::uniform_real_distribution<double> radius(r_min, r_max);
  Ring ring;
  for (int k = 0; k < vertices; ++k) {
    const double a = (clockwise ? -1.0 : 1.0) * 2.0 * std::numbers::pi * k / vertices;
    const double r = radius(rng);
    ring.push_back(centre + Vec2{std::cos(a), std::sin(a)} * r);
  }
  return ring;
}

// A lake: a noisy 600-vertex outline with two islands (holes), plus a concave comb and many
// small random polygons, around (500 000, 5 000 000) in metres.
inline std::vector<Polygon> realistic_polygons() {
  std::mt19937 rng(2013);
  const Vec2 o{500000.0, 5000000.0};
  std::vector<Polygon> polys;
  Polygon lake;
  Ring outline;
  for (int k = 0; k < 600; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 600;
    const double r = 300.0 + 60.0 * std::sin(5 * a) + 25.0 * std::sin(17 * a + 1.0) +
                     std::uniform_real_distribution<double>(-6.0, 6.0)(rng);
    outline.push_back(o + Vec2{420.0, 380.0} + Vec2{std::cos(a) * r, std::sin(a) * r * 0.8});
  }
  lake.push_back(outline);
  lake.push_back(random_star(rng, o + Vec2{380.0, 400.0}, 40.0, 70.0, 40, true));
  lake.push_back(random_star(rng, o + Vec2{520.0, 300.0}, 20.0, 35.0, 25));
  polys.push_back(lake);
  // A comb (very concave) with 12 teeth.
  Ring comb{o + Vec2{820, 60}};
  for (int t = 0; t < 12; ++t) {
    const double x = 820.0 + t * 20.3;
    comb.push_back(o + Vec2{x, 300.7});
    comb.push_back(o + Vec2{x + 9.1, 300.7});
    comb.push_back(o + Vec2{x + 9.1, 90.2});
    comb.push_back(o + Vec2{x + 20.3, 90.2});
  }
  comb.push_back(o + Vec2{820 + 12 * 20.3, 60});
  polys.push_back({comb});
  for (int i = 0; i < 60; ++i) {
    std::uniform_real_distribution<double> px(0.0, 1250.0), py(0.0, 780.0);
    polys.push_back({random_star(rng, o + Vec2{px(rng), py(rng)}, 5.0, 45.0,
                                 std::uniform_int_distribution<int>(3, 60)(rng))});
  }
  return polys;
}

}  // namespace tw::test
