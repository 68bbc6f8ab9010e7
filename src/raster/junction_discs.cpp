#include "raster/junction_discs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace tw {

std::vector<Polygon> junction_discs(const std::vector<Junction>& junctions,
                                    const std::vector<double>& radii, int sides) {
  if (junctions.size() != radii.size())
    fail("junction_discs: {} junctions but {} radii", junctions.size(), radii.size());
  if (sides < 8) fail("junction_discs: need at least 8 sides (got {})", sides);
  // Circumscribed polygon: its edges' midpoints touch the circle, so the disc is inside.
  const double scale = 1.0 / std::cos(std::numbers::pi / sides);
  std::vector<Polygon> discs;
  discs.reserve(junctions.size());
  for (std::size_t j = 0; j < junctions.size(); ++j) {
    if (!(radii[j] >= 0.0) || !std::isfinite(radii[j]))
      fail("junction {}: disc radius {} m is not >= 0", j, radii[j]);
    Ring ring;
    ring.reserve(std::size_t(sides));
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * std::numbers::pi * k / sides;
      ring.push_back(junctions[j].position + Vec2{std::cos(a), std::sin(a)} * (radii[j] * scale));
    }
    discs.push_back({std::move(ring)});
  }
  return discs;
}

double junction_disc_radius(const std::vector<double>& member_widths_m, double margin_m) {
  double widest = 0.0;
  for (const double w : member_widths_m) widest = std::max(widest, w);
  return widest / 2.0 + margin_m;
}

}  // namespace tw
