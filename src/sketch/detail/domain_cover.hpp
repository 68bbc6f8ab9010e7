#pragma once
// A coarse lattice over an area's polygon that answers most placement questions without
// walking the polygon's edges: cells wholly inside, wholly outside, or crossed by the boundary.
// A shape box over inside cells only is within the polygon; one centred on an outside cell is
// not; the rest (near the boundary, in proportion to its length) go to the exact test. Its cells
// are bounded (kMaxCells), whatever the polygon's size.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"

namespace tw::detail {

class DomainCover {
 public:
  static constexpr double kMaxCells = double(1 << 22);

  // Cells of `cell` metres, or coarser when the polygon's box would need more than kMaxCells.
  DomainCover(const Polygon& domain, double cell);

  // False only when no point of the polygon lies within `reach` metres of p.
  bool near(Vec2 p, double reach) const;
  // Whether the convex quadrilateral lies within the polygon, when the cells under it say so.
  std::optional<bool> contains(const std::array<Vec2, 4>& corners) const;
  double cell() const { return grid_.pixel_width; }

 private:
  enum State : std::uint8_t { outside = 0, inside = 1, boundary = 2 };
  State state(int col, int row) const;
  GridSpec grid_;
  std::vector<std::uint8_t> states_;
};

}  // namespace tw::detail
