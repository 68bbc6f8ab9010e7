#include "network/detail/layout_copies.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/boost_geometry.hpp"
#include "network/detail/skeleton.hpp"

namespace tw::network_detail {

namespace {

using namespace geometry;

// A polyline with one end (the last point when `at_back`) moved along the line: `by` > 0
// metres further straight ahead along its end segment, `by` < 0 metres back along the line
// (empty when that leaves nothing).
std::vector<Vec2> moved_free_end(std::vector<Vec2> pts, bool at_back, double by) {
  if (!at_back) std::reverse(pts.begin(), pts.end());
  if (by >= 0.0) {
    const double heading = leaving_heading(pts, false) + std::numbers::pi;
    pts.back() = pts.back() + Vec2{std::cos(heading), std::sin(heading)} * by;
  } else {
    double left = -by;
    while (pts.size() >= 2) {
      const double last = distance(pts[pts.size() - 2], pts.back());
      if (last > left) {
        pts.back() = lerp(pts.back(), pts[pts.size() - 2], left / last);
        break;
      }
      left -= last;
      pts.pop_back();
    }
    if (pts.size() < 2) return {};
  }
  if (!at_back) std::reverse(pts.begin(), pts.end());
  return pts;
}

}  // namespace

struct LayoutCopies::Lines {
  bgi::rtree<BgSegment, bgi::quadratic<16>> index;
};

LayoutCopies::LayoutCopies(const Network& exemplar, const LayoutFrame& frame)
    : lines_(std::make_unique<Lines>()), frame_(frame) {
  for (const NetworkEdge& edge : exemplar.edges)
    for (std::size_t k = 0; k + 1 < edge.points.size(); ++k)
      lines_->index.insert(BgSegment(to_bg(edge.points[k]), to_bg(edge.points[k + 1])));
}
LayoutCopies::~LayoutCopies() = default;
LayoutCopies::LayoutCopies(LayoutCopies&&) noexcept = default;
LayoutCopies& LayoutCopies::operator=(LayoutCopies&&) noexcept = default;

Vec2 LayoutFrame::place(Vec2 q, int i, int j) const {
  const Vec2 tile{i * size.x, j * size.y};
  return islands ? origin + tile + rotated(q - centre, turn)
                 : origin + rotated(q - centre + tile, turn);
}

bool LayoutCopies::empty_near(Vec2 p, double reach) const {
  const LayoutFrame& f = frame_;
  if (lines_->index.empty()) return false;
  // p on the copies' grid, relative to its origin.
  const Vec2 g = f.islands ? p - f.origin : rotated(p - f.origin, -f.turn);
  const Vec2 q = g + f.centre;
  const Vec2 copies{f.ni * f.size.x, f.nj * f.size.y};
  if (q.x < f.lo.x - copies.x || q.y < f.lo.y - copies.y || q.x > f.hi.x + copies.x ||
      q.y > f.hi.y + copies.y)
    return false;
  // The copy p lies in and its neighbours (a line of the next copy may be nearer).
  const int i0 = int(std::lround(g.x / f.size.x));
  const int j0 = int(std::lround(g.y / f.size.y));
  for (int j = std::max(j0 - 1, -f.nj); j <= std::min(j0 + 1, f.nj); ++j)
    for (int i = std::max(i0 - 1, -f.ni); i <= std::min(i0 + 1, f.ni); ++i) {
      const Vec2 tile{i * f.size.x, j * f.size.y};
      const BgPoint in_copy = to_bg(f.islands ? rotated(g - tile, -f.turn) + f.centre : q - tile);
      std::vector<BgSegment> near;
      lines_->index.query(bgi::nearest(in_copy, 1), std::back_inserter(near));
      if (!near.empty() && bg::distance(near[0], in_copy) < reach) return false;
    }
  return true;
}

bool LayoutCopies::corners_empty(double reach) const {
  const LayoutFrame& f = frame_;
  for (Vec2 q : {f.lo, f.hi, Vec2{f.lo.x, f.hi.y}, Vec2{f.hi.x, f.lo.y}})
    if (!empty_near(f.place(q, 0, 0), reach)) return false;
  return true;
}

std::vector<Vec2> with_free_ends_clear(std::vector<Vec2> pts, bool front, bool back,
                                       double clearance, const std::function<bool(Vec2)>& clear) {
  for (int end = 0; end < 2; ++end) {
    const bool at_back = end == 1;
    if (!(at_back ? back : front) || clear(at_back ? pts.back() : pts.front())) continue;
    std::vector<Vec2> moved;
    for (int step = 1; step <= 30 && moved.empty(); ++step)
      for (double by : {-0.1 * step * clearance, 0.1 * step * clearance}) {
        std::vector<Vec2> q = moved_free_end(pts, at_back, by);
        if (!q.empty() && clear(at_back ? q.back() : q.front())) {
          moved = std::move(q);
          break;
        }
      }
    if (moved.empty()) return {};
    pts = std::move(moved);
  }
  return pts;
}

}  // namespace tw::network_detail
