#include "network/detail/box_clip.hpp"

#include <algorithm>
#include <cmath>

namespace tw::network_detail {

void cut_to_box(const std::vector<Vec2>& pts, Vec2 lo, Vec2 hi,
                std::vector<std::vector<Vec2>>& out) {
  const auto in = [&](Vec2 p) { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; };
  // Parameters where ab crosses the box's sides.
  const auto crossings = [&](Vec2 a, Vec2 b) {
    std::vector<double> ts;
    for (double t : {(lo.x - a.x) / (b.x - a.x), (hi.x - a.x) / (b.x - a.x),
                     (lo.y - a.y) / (b.y - a.y), (hi.y - a.y) / (b.y - a.y)})
      if (std::isfinite(t) && t > 0.0 && t < 1.0) ts.push_back(t);
    std::sort(ts.begin(), ts.end());
    return ts;
  };
  std::vector<Vec2> part;
  const auto flush = [&]() {
    if (part.size() >= 2) out.push_back(part);
    part.clear();
  };
  if (in(pts[0])) part.push_back(pts[0]);
  for (std::size_t k = 1; k < pts.size(); ++k) {
    const Vec2 a = pts[k - 1], b = pts[k];
    double previous = 0.0;
    for (double t : crossings(a, b)) {
      const Vec2 p = lerp(a, b, t);
      const bool was_in = in(lerp(a, b, 0.5 * (previous + t)));
      if (was_in) {
        part.push_back(p);
        flush();
      } else {
        part.push_back(p);
      }
      previous = t;
    }
    if (in(b))
      part.push_back(b);
    else
      flush();
  }
  flush();
}

}  // namespace tw::network_detail
