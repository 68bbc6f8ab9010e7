#pragma once
// Footprints in vector space (world metres): a line buffered by its half width, or an area.
// What grown lines keep off is decided here, exactly, on the vector lines themselves, never on
// the growth mesh: a 1-3 m footprint slips between the vertices of an 8-10 m mesh, so a mask
// rasterized on it lets lines through (issue #21). Two footprints overlap when their lines come
// closer than the sum of their half widths (Boost.Geometry's segment distance; an R-tree of the
// segments' boxes finds the candidates).
#include <cstdint>
#include <memory>
#include <vector>

#include "core/vec2.hpp"
#include "raster/polygon.hpp"

namespace tw {

class FootprintIndex {
 public:
  FootprintIndex();
  ~FootprintIndex();
  FootprintIndex(FootprintIndex&&) noexcept;
  FootprintIndex& operator=(FootprintIndex&&) noexcept;

  // Each returns the footprint's id: 0, 1, ... in the order added. A line of one point is a
  // disc; `half_width` 0 is the line itself.
  int add_line(const std::vector<Vec2>& points, double half_width);
  int add_polygon(const Polygon& polygon);
  int size() const;

  // Whether `polyline` buffered by `half_width` overlaps a footprint: it comes closer to a line
  // than the sum of their half widths, or closer to an area than its own half width.
  bool overlaps(const std::vector<Vec2>& polyline, double half_width) const;
  // The ids of the footprints it overlaps, ascending.
  std::vector<int> overlapped(const std::vector<Vec2>& polyline, double half_width) const;
  // The ids of the lines that `polyline` crosses (its centre line meets theirs), ascending.
  // Lines may meet end to end: a point that ends both lines (an ornament's joint) is not a
  // crossing unless the two run along each other from it.
  std::vector<int> crossed(const std::vector<Vec2>& polyline) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tw
