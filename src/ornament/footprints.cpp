#include "ornament/footprints.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "core/boost_geometry.hpp"

namespace tw {

namespace {

using namespace geometry;
// A segment's (or an area's) box and where it comes from: footprint id, segment number (-1 for
// an area).
using Entry = std::pair<BgBox, std::pair<int, int>>;

BgBox box_of(Vec2 a, Vec2 b, double pad) {
  return {{std::min(a.x, b.x) - pad, std::min(a.y, b.y) - pad},
          {std::max(a.x, b.x) + pad, std::max(a.y, b.y) + pad}};
}

// The polyline's segments; one point is a segment of length zero (a disc once buffered).
std::vector<std::pair<Vec2, Vec2>> segments_of(const std::vector<Vec2>& points) {
  std::vector<std::pair<Vec2, Vec2>> out;
  if (points.size() == 1) out.emplace_back(points[0], points[0]);
  for (std::size_t k = 0; k + 1 < points.size(); ++k) out.emplace_back(points[k], points[k + 1]);
  return out;
}

}  // namespace

struct FootprintIndex::Impl {
  struct Footprint {
    std::vector<Vec2> points;  // a line (empty for an area)
    double half_width = 0.0;
    std::optional<BgPolygon> area;
  };
  std::vector<Footprint> footprints;
  bgi::rtree<Entry, bgi::rstar<16>> tree;
  double widest = 0.0;  // the largest half width: how far a query box must reach

  // Calls visit(id, k) for every stored segment or area whose box comes within `reach` of a-b.
  template <class Visit>
  void near(Vec2 a, Vec2 b, double reach, Visit&& visit) const {
    std::vector<Entry> hits;
    tree.query(bgi::intersects(box_of(a, b, reach)), std::back_inserter(hits));
    for (const Entry& e : hits) visit(e.second.first, e.second.second);
  }
};

FootprintIndex::FootprintIndex() : impl_(std::make_unique<Impl>()) {}
FootprintIndex::~FootprintIndex() = default;
FootprintIndex::FootprintIndex(FootprintIndex&&) noexcept = default;
FootprintIndex& FootprintIndex::operator=(FootprintIndex&&) noexcept = default;

int FootprintIndex::add_line(const std::vector<Vec2>& points, double half_width) {
  const int id = size();
  const auto segments = segments_of(points);
  for (std::size_t k = 0; k < segments.size(); ++k)
    impl_->tree.insert({box_of(segments[k].first, segments[k].second, 0.0), {id, int(k)}});
  impl_->footprints.push_back({points, half_width, std::nullopt});
  impl_->widest = std::max(impl_->widest, half_width);
  return id;
}

int FootprintIndex::add_polygon(const Polygon& polygon) {
  const int id = size();
  BgPolygon area;
  for (std::size_t r = 0; r < polygon.size(); ++r) {
    auto& ring = r == 0 ? area.outer() : area.inners().emplace_back();
    for (Vec2 p : polygon[r]) ring.push_back(to_bg(p));
  }
  bg::correct(area);  // closes the rings and orients them as Boost expects
  if (area.outer().empty()) return id;
  BgBox box;
  bg::envelope(area, box);
  impl_->tree.insert({box, {id, -1}});
  impl_->footprints.push_back({{}, 0.0, std::move(area)});
  return id;
}

int FootprintIndex::size() const {
  return int(impl_->footprints.size());
}

std::vector<int> FootprintIndex::overlapped(const std::vector<Vec2>& polyline,
                                            double half_width) const {
  std::vector<int> out;
  for (const auto& [a, b] : segments_of(polyline)) {
    const BgSegment s(to_bg(a), to_bg(b));
    impl_->near(a, b, half_width + impl_->widest, [&](int id, int k) {
      const Impl::Footprint& f = impl_->footprints[std::size_t(id)];
      if (k < 0) {
        // Inside an area the distance is 0: a line of width 0 there overlaps it too.
        const double d = bg::distance(s, *f.area);
        if (d < half_width || d == 0.0) out.push_back(id);
        return;
      }
      const Vec2 c = f.points[std::size_t(k)],
                 e = f.points[std::min(std::size_t(k) + 1, f.points.size() - 1)];
      const double reach = half_width + f.half_width;
      const BgSegment t(to_bg(c), to_bg(e));
      if (reach > 0.0 ? bg::distance(s, t) < reach : bg::intersects(s, t)) out.push_back(id);
    });
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool FootprintIndex::overlaps(const std::vector<Vec2>& polyline, double half_width) const {
  return !overlapped(polyline, half_width).empty();
}

std::vector<int> FootprintIndex::crossed(const std::vector<Vec2>& polyline) const {
  std::vector<int> out;
  if (polyline.empty()) return out;
  const Vec2 first = polyline.front(), last = polyline.back();
  for (const auto& [a, b] : segments_of(polyline)) {
    const BgSegment s(to_bg(a), to_bg(b));
    impl_->near(a, b, 0.0, [&](int id, int k) {
      if (k < 0) return;  // areas are not crossed, they are overlapped
      const Impl::Footprint& f = impl_->footprints[std::size_t(id)];
      const Vec2 c = f.points[std::size_t(k)],
                 e = f.points[std::min(std::size_t(k) + 1, f.points.size() - 1)];
      if (!bg::intersects(s, BgSegment(to_bg(c), to_bg(e)))) return;
      // Meeting end to end: a shared point that ends both lines and both segments, where the
      // segments do not run along each other (collinear and the same way from it).
      for (Vec2 joint : {first, last}) {
        if (joint != f.points.front() && joint != f.points.back()) continue;
        if ((a != joint && b != joint) || (c != joint && e != joint)) continue;
        const Vec2 u = (a == joint ? b : a) - joint, v = (c == joint ? e : c) - joint;
        if (cross(u, v) != 0.0 || dot(u, v) <= 0.0) return;
      }
      out.push_back(id);
    });
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace tw
