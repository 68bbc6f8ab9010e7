// The module's second CGAL translation unit: exact segment predicates (Epick's filtered
// do_intersect and collinear), squared distances between segments.
#include "ornament/segment_index.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>

namespace tw {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Segment2 = Kernel::Segment_2;

Point point(Vec2 v) {
  return {v.x, v.y};
}

}  // namespace

SegmentIndex::SegmentIndex(double cell_m) : cell_(cell_m) {}
SegmentIndex::~SegmentIndex() = default;
SegmentIndex::SegmentIndex(SegmentIndex&&) noexcept = default;

void SegmentIndex::insert(const std::vector<Vec2>& polyline) {
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vec2 a = polyline[k], b = polyline[k + 1];
    const int id = int(segments_.size());
    segments_.push_back({a, b});
    const int x0 = int(std::floor(std::min(a.x, b.x) / cell_)),
              x1 = int(std::floor(std::max(a.x, b.x) / cell_));
    const int y0 = int(std::floor(std::min(a.y, b.y) / cell_)),
              y1 = int(std::floor(std::max(a.y, b.y) / cell_));
    for (int cy = y0; cy <= y1; ++cy) {
      for (int cx = x0; cx <= x1; ++cx) cells_[key(cx, cy)].push_back(id);
    }
  }
}

bool SegmentIndex::conflicts(const std::vector<Vec2>& polyline, Vec2 joint,
                             double clearance) const {
  std::vector<int> seen;
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vec2 a = polyline[k], b = polyline[k + 1];
    const Segment2 s(point(a), point(b));
    const bool near_joint = distance(a, joint) < clearance || distance(b, joint) < clearance;
    const double reach = near_joint ? 0.0 : clearance;
    const int x0 = int(std::floor((std::min(a.x, b.x) - reach) / cell_)),
              x1 = int(std::floor((std::max(a.x, b.x) + reach) / cell_));
    const int y0 = int(std::floor((std::min(a.y, b.y) - reach) / cell_)),
              y1 = int(std::floor((std::max(a.y, b.y) + reach) / cell_));
    seen.clear();
    for (int cy = y0; cy <= y1; ++cy) {
      for (int cx = x0; cx <= x1; ++cx) {
        const auto it = cells_.find(key(cx, cy));
        if (it == cells_.end()) continue;
        for (int id : it->second) {
          if (std::find(seen.begin(), seen.end(), id) != seen.end()) continue;
          seen.push_back(id);
          const Segment& t = segments_[std::size_t(id)];
          const Segment2 u(point(t.a), point(t.b));
          if (CGAL::do_intersect(s, u)) {
            // Meeting end to end at the joint is how an ornament grows; anything else (or an
            // overlap along a common line) is a crossing.
            const bool at_joint = (a == joint || b == joint) && (t.a == joint || t.b == joint);
            const auto common = CGAL::intersection(s, u);
            const bool overlap = common && boost::get<Segment2>(&*common) != nullptr;
            if (!at_joint || overlap) return true;
            continue;
          }
          if (reach > 0.0 && CGAL::squared_distance(s, u) < clearance * clearance) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace tw
