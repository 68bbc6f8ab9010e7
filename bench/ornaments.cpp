// FloralSurf ornaments (docs/ornaments.md): growth time against the region's size and the number
// of ornaments, the time per placed element, and the process's peak RSS (the heat method's
// factorization dominates memory), with each element's distances solved on the part of the
// mesh they can change (local, the default) or on the whole mesh (whole, the reference).
// Prints numbers; never fails on time.
//   bench_ornaments [max_side (256)] [whole_max_side (128)]
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "ornament/grow.hpp"

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

long peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

// An n x n hillside at 2 m with rolling bumps, all of it allowed but a 6 m road.
void run(const tw::ElementSet& set, const char* name, int n, int max_ornaments, bool local) {
  const tw::GridSpec grid{n, n, 0.0, 2.0 * n, 2.0, 2.0};
  tw::Raster<float> heights(n, n);
  tw::Raster<std::uint8_t> allowed(n, n, 1);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const tw::Vec2 p = grid.pixel_centre_world(c, r);
      heights.at(c, r) = float(0.15 * p.y + 3.0 * std::sin(p.x / 23.0) * std::cos(p.y / 31.0));
      if (std::abs(p.x - n * 0.7) < 3.0) allowed.at(c, r) = 0;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const tw::TerrainSurface surface(heights, grid, tw::Window::whole(grid));
  tw::GrowthParams params;
  params.seed = 1;
  params.max_ornaments = max_ornaments;
  params.local_distances = local;
  const tw::GrowthResult r = tw::grow_ornaments(surface, allowed, set, params);
  const double ms = ms_since(t0);
  const double coverage = tw::ornament_coverage(surface, allowed, r.lines, set.scale_m / 2);
  std::printf(
      "%-6s %-5s %5d^2 vertices (%4.0f m)  ornaments<=%-4d: %3d ornaments %5d elements  "
      "%9.0f ms  %7.2f ms/element  solves %d local %d whole  coverage %.3f  peak RSS %ld MB\n",
      name, local ? "local" : "whole", n, 2.0 * n, max_ornaments, r.ornaments, r.elements, ms,
      ms / std::max(r.elements, 1), r.local_solves, r.whole_solves, coverage, peak_rss_mb());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int max_side = argc > 1 ? std::atoi(argv[1]) : 256;
  const int whole_max_side = argc > 2 ? std::atoi(argv[2]) : 128;
  for (const char* name : {"hedge", "ditch"}) {
    const tw::ElementSet set = tw::read_element_set(std::string(TERRAWEAVE_SOURCE_DIR) +
                                                    "/samples/ornaments/" + name + ".json");
    for (int n = 64; n <= max_side; n *= 2) {
      run(set, name, n, 1000, true);
      if (n <= whole_max_side) run(set, name, n, 1000, false);
    }
    for (int ornaments : {1, 4, 16}) run(set, name, 128, ornaments, true);
  }
}
