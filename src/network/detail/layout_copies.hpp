#pragma once
// What the layout (docs/networks.md, "Layout") keeps of the exemplar besides its long strokes:
// its empty parts (no lattice seed where the copies have no line: beyond a radial network's
// outer ring; turned copies of such an exemplar are islands, LayoutFrame) and its dangling ends
// (moved to keep the clearance, not dropped).
#include <functional>
#include <memory>
#include <vector>

#include "network/network.hpp"

namespace tw::network_detail {

// The exemplar as the layout copies it: copy (i, j), |i| <= ni, |j| <= nj, of exemplar point q
// lies at origin + rotated(q - centre + (i size.x, j size.y), turn) when the copies join (their
// grid turns with them), at origin + (i size.x, j size.y) + rotated(q - centre, turn) when they
// are islands (the exemplar's corners empty: each copy turns about its own centre, and the
// region's corners stay as empty as the exemplar's); [lo, hi] is the exemplar's extent.
struct LayoutFrame {
  Vec2 origin, centre, size, lo, hi;
  double turn = 0.0;
  int ni = 0, nj = 0;
  bool islands = false;

  Vec2 place(Vec2 q, int i, int j) const;
};

class LayoutCopies {
 public:
  LayoutCopies(const Network& exemplar, const LayoutFrame& frame);
  ~LayoutCopies();
  LayoutCopies(LayoutCopies&&) noexcept;
  LayoutCopies& operator=(LayoutCopies&&) noexcept;

  // Whether p lies within the copies with no exemplar line within `reach` (of the copy p lies
  // in or a neighbouring one); false beyond the copies.
  bool empty_near(Vec2 p, double reach) const;
  // Whether the exemplar's four extent corners are empty_near (copies tiled at them meet no
  // line there): the copies are islands.
  bool corners_empty(double reach) const;

 private:
  struct Lines;
  std::unique_ptr<Lines> lines_;
  LayoutFrame frame_;
};

// A copied line whose dangling ends (`front`, `back`: ends of degree 1 in the exemplar) are not
// `clear` (within the clearance of a line) with those ends moved along it, in steps of a tenth
// of `clearance`, until they are: back when the line is long enough, else on straight past the
// line it crossed. Empty when no move within three clearances is clear.
std::vector<Vec2> with_free_ends_clear(std::vector<Vec2> points, bool front, bool back,
                                       double clearance, const std::function<bool(Vec2)>& clear);

}  // namespace tw::network_detail
