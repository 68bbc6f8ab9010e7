// Structured shape-patterns in areas (docs/shape-patterns.md): analysis time against the number
// of strokes, synthesis time against the area filled, and the process's peak RSS. Prints numbers;
// never fails on time.
//   bench_areas
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sketch/area_synthesis.hpp"

namespace {

using tw::Vec2;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

tw::Stroke ring(Vec2 c, double r) {
  tw::Stroke s;
  for (int k = 0; k <= 12; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 12.0;
    s.points.push_back(c + Vec2{std::cos(a), std::sin(a)} * r);
  }
  s.thickness = 0.2 * r;
  return s;
}

// rows x per_row posts, each row with its wire: rows * (per_row + 1) strokes.
tw::Sketch vineyard(int rows, int per_row) {
  tw::Sketch sketch;
  sketch.source = "bench";
  for (int row = 0; row < rows; ++row) {
    const double y = (row + 0.5) / rows;
    tw::Stroke wire;
    wire.points = {{0.0, y + 0.15 / rows}, {1.0, y + 0.15 / rows}};
    wire.unbounded = true;
    wire.thickness = 0.05 / rows;
    sketch.strokes.push_back(wire);
    for (int k = 0; k < per_row; ++k) {
      sketch.strokes.push_back(ring({(k + 0.5) / per_row, y}, 0.12 / std::max(rows, per_row)));
    }
  }
  return sketch;
}

long peak_rss_kib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

}  // namespace

int main() {
  std::printf("analysis (Support Structure Hierarchy):\n%8s %8s %10s %12s\n", "strokes", "shapes",
              "ms", "us/stroke");
  for (int n : {4, 8, 16, 32}) {
    const tw::Sketch sketch = vineyard(n, n);
    const auto t0 = std::chrono::steady_clock::now();
    const tw::SupportHierarchy h = tw::analyze_sketch(sketch);
    const double ms = ms_since(t0);
    std::printf("%8zu %8zu %10.2f %12.1f\n", sketch.strokes.size(), h.shapes.size(), ms,
                1000.0 * ms / double(sketch.strokes.size()));
  }
  const tw::SupportHierarchy h = tw::analyze_sketch(vineyard(5, 10));
  std::printf(
      "\nsynthesis (vineyard sketch, 5 rows x 10 posts, 40 m a side):\n%8s %10s %10s %10s "
      "%12s\n",
      "side m", "km2", "instances", "ms", "ms/1000 inst");
  double first_rate = 0.0;
  for (double side : {200.0, 400.0, 800.0, 1600.0}) {
    const tw::Polygon square{{{0, 0}, {side, 0}, {side, side}, {0, side}}};
    tw::AreaSynthesisParams params;
    params.scale = 40.0;
    params.bearing = 0.3;
    const auto t0 = std::chrono::steady_clock::now();
    const tw::AreaPattern p = tw::synthesize_area(h, square, params);
    const double ms = ms_since(t0);
    const double rate = 1000.0 * ms / double(p.instances.size());
    if (first_rate == 0.0) first_rate = rate;
    std::printf("%8.0f %10.3f %10zu %10.1f %12.2f (x%.2f)\n", side, side * side / 1e6,
                p.instances.size(), ms, rate, rate / first_rate);
  }
  std::printf("\npeak RSS: %.1f MiB\n", double(peak_rss_kib()) / 1024.0);
}
