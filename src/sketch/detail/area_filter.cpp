#include "sketch/detail/area_filter.hpp"

// GCC 12 sees maybe-uninitialized values inside Boost.Geometry's envelope and rescaling code
// once inlined here (false positives in the library's headers); ours stays -Wall clean.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/index/rtree.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <map>

namespace tw::detail {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BgPoint = bg::model::d2::point_xy<double>;
using BgLine = bg::model::linestring<BgPoint>;
using BgLines = bg::model::multi_linestring<BgLine>;
using BgPolygon = bg::model::polygon<BgPoint>;
using BgBox = bg::model::box<BgPoint>;

namespace {

BgPoint to_bg(Vec2 p) {
  return {p.x, p.y};
}

BgPolygon to_bg(const Polygon& polygon) {
  BgPolygon out;
  for (std::size_t r = 0; r < polygon.size(); ++r) {
    auto& ring = r == 0 ? out.outer() : out.inners().emplace_back();
    for (Vec2 p : polygon[r]) ring.push_back(to_bg(p));
  }
  bg::correct(out);  // closes the rings and orients them as boost expects
  return out;
}

BgLine to_bg(const std::vector<Vec2>& line) {
  BgLine out;
  for (Vec2 p : line) out.push_back(to_bg(p));
  return out;
}

// The oriented box of points along `axis`, padded.
BgPolygon oriented_box(const std::vector<std::vector<Vec2>>& strokes, Vec2 axis, double pad) {
  const Vec2 normal = perp(axis);
  double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
  for (const auto& s : strokes)
    for (Vec2 p : s) {
      a0 = std::min(a0, dot(p, axis)), a1 = std::max(a1, dot(p, axis));
      b0 = std::min(b0, dot(p, normal)), b1 = std::max(b1, dot(p, normal));
    }
  a0 -= pad, a1 += pad, b0 -= pad, b1 += pad;
  BgPolygon box;
  for (auto [a, b] : {std::pair{a0, b0}, {a1, b0}, {a1, b1}, {a0, b1}}) {
    box.outer().push_back(to_bg(axis * a + normal * b));
  }
  bg::correct(box);
  return box;
}

// What is placed: a bounded shape's box or one segment of an unbounded stroke.
struct Placed {
  std::size_t candidate = 0;
  int shape = 0;
  bool unbounded = false;
  BgPolygon box;
  BgLine segment;
  double half_width = 0.0;
};
using Tree = bgi::rtree<std::pair<BgBox, std::size_t>, bgi::rstar<16>>;

class Overlaps {
 public:
  explicit Overlaps(const SupportHierarchy& h) : h_(h) {}

  // True when `shape`'s geometry meets a placed shape that it was disjoint from in the sketch.
  template <class Geometry>
  bool conflict(std::size_t candidate, int shape, const Geometry& geometry, double half_width) {
    BgBox bounds;
    bg::envelope(geometry, bounds);
    const double m = half_width + max_half_width_;
    BgBox query(BgPoint(bounds.min_corner().x() - m, bounds.min_corner().y() - m),
                BgPoint(bounds.max_corner().x() + m, bounds.max_corner().y() + m));
    std::vector<std::pair<BgBox, std::size_t>> hits;
    tree_.query(bgi::intersects(query), std::back_inserter(hits));
    std::sort(hits.begin(), hits.end(), [](auto& a, auto& b) { return a.second < b.second; });
    for (const auto& [box, index] : hits) {
      const Placed& other = placed_[index];
      if (other.candidate == candidate || overlapped_in_sketch(shape, other.shape)) continue;
      const double d = other.unbounded ? bg::distance(geometry, other.segment)
                                       : bg::distance(geometry, other.box);
      if (d <= half_width + other.half_width) return true;
    }
    return false;
  }

  void add(Placed placed) {
    BgBox bounds;
    if (placed.unbounded) {
      bg::envelope(placed.segment, bounds);
    } else {
      bg::envelope(placed.box, bounds);
    }
    max_half_width_ = std::max(max_half_width_, placed.half_width);
    tree_.insert({bounds, placed_.size()});
    placed_.push_back(std::move(placed));
  }

 private:
  // Distinct shapes whose strokes came within their thicknesses in the sketch may meet again.
  bool overlapped_in_sketch(int a, int b) {
    if (a == b) return false;
    const auto key = std::minmax(a, b);
    if (auto it = sketch_overlap_.find(key); it != sketch_overlap_.end()) return it->second;
    bool meet = false;
    for (int sa : h_.shapes[std::size_t(a)].strokes)
      for (int sb : h_.shapes[std::size_t(b)].strokes) {
        const Stroke &x = h_.sketch.strokes[std::size_t(sa)],
                     &y = h_.sketch.strokes[std::size_t(sb)];
        meet = meet ||
               bg::distance(to_bg(x.points), to_bg(y.points)) <= 0.5 * (x.thickness + y.thickness);
      }
    sketch_overlap_[key] = meet;
    return meet;
  }

  const SupportHierarchy& h_;
  std::vector<Placed> placed_;
  Tree tree_;
  double max_half_width_ = 0.0;
  std::map<std::pair<int, int>, bool> sketch_overlap_;
};

// Conservatively free: every point within half_width of the segment is farther than that from
// any forbidden pixel centre (the distance field is exact at pixel centres; a point is within
// half a diagonal of its pixel's centre).
bool segment_free(const AvoidanceMap& a, Vec2 p, Vec2 q, double half_width) {
  const double diagonal = std::hypot(a.grid.pixel_width, a.grid.pixel_height);
  const double margin = half_width + 0.5 * diagonal + 0.5 * distance(p, q);
  const Vec2 mid = (p + q) * 0.5;
  const Vec2 px = a.grid.world_to_pixel(mid);
  const int col = int(std::floor(px.x)) - a.window.col0,
            row = int(std::floor(px.y)) - a.window.row0;
  if (col < 0 || row < 0 || col >= a.window.width || row >= a.window.height) return true;
  return a.distance.at(col, row) > margin;
}

bool shape_free(const AvoidanceMap& a, const std::vector<std::vector<Vec2>>& strokes,
                const std::vector<double>& widths) {
  for (std::size_t s = 0; s < strokes.size(); ++s)
    for (std::size_t i = 0; i + 1 < strokes[s].size(); ++i)
      if (!segment_free(a, strokes[s][i], strokes[s][i + 1], 0.5 * widths[s])) return false;
  return true;
}

// The polyline with no segment longer than `step`.
std::vector<Vec2> densified(const std::vector<Vec2>& line, double step) {
  std::vector<Vec2> out{line.front()};
  for (std::size_t i = 1; i < line.size(); ++i) {
    const int n = std::max(1, int(std::ceil(distance(line[i - 1], line[i]) / step)));
    for (int k = 1; k <= n; ++k) out.push_back(lerp(line[i - 1], line[i], double(k) / n));
  }
  return out;
}

}  // namespace

AreaPattern place_candidates(const SupportHierarchy& h, const std::vector<Candidate>& candidates,
                             const Polygon& domain, const std::function<Vec2(Vec2)>& to_world,
                             double scale, const AvoidanceMap* avoidance, double densify) {
  AreaPattern out;
  const BgPolygon region = to_bg(domain);
  Overlaps overlaps(h);
  const double step =
      avoidance ? 0.5 * std::min(avoidance->grid.pixel_width, avoidance->grid.pixel_height)
                : 0.01 * scale;
  for (std::size_t ci = 0; ci < candidates.size(); ++ci) {
    const Candidate& c = candidates[ci];
    const SketchShape& shape = h.shapes[std::size_t(c.shape)];
    std::vector<std::vector<Vec2>> strokes;
    std::vector<double> widths;
    double half_width = 0.0;
    for (std::size_t s = 0; s < c.strokes.size(); ++s) {
      auto& world = strokes.emplace_back();
      for (Vec2 q : densify > 0.0 ? densified(c.strokes[s], densify) : c.strokes[s])
        world.push_back(to_world(q));
      widths.push_back(h.sketch.strokes[std::size_t(shape.strokes[s])].thickness * scale);
      half_width = std::max(half_width, 0.5 * widths.back());
    }
    const Vec2 centre = to_world(c.centre);
    // The axis's image over one input unit when affine; over `densify` when curved.
    const Vec2 axis =
        normalized(to_world(c.centre + c.axis * (densify > 0.0 ? densify : 1.0)) - centre);
    ShapeInstance instance{
        c.shape,    c.lead,
        centre,     std::atan2(axis.y, axis.x),
        scale,      h.sketch.strokes[std::size_t(shape.strokes.front())].material,
        c.unbounded};
    const int instance_index = int(out.instances.size());
    if (!c.unbounded) {
      const BgPolygon box = oriented_box(strokes, axis, half_width);
      if (!bg::within(box, region)) {
        ++out.outside;
        continue;
      }
      if (avoidance && !shape_free(*avoidance, strokes, widths)) {
        ++out.forbidden;
        continue;
      }
      if (overlaps.conflict(ci, c.shape, box, 0.0)) {
        ++out.overlapping;
        continue;
      }
      overlaps.add({ci, c.shape, false, box, {}, 0.0});
      out.instances.push_back(instance);
      for (std::size_t s = 0; s < strokes.size(); ++s) {
        out.strokes.push_back({strokes[s], h.sketch.strokes[std::size_t(shape.strokes[s])].material,
                               widths[s], instance_index});
      }
      continue;
    }
    // Unbounded: clipped to the polygon, then cut where a segment is forbidden or meets a shape
    // it was disjoint from; pieces shorter than the stroke's width are dropped.
    bool kept = false, any_forbidden = false, any_overlap = false;
    for (std::size_t s = 0; s < strokes.size(); ++s) {
      BgLines clipped;
      bg::intersection(to_bg(strokes[s]), region, clipped);
      const double half = 0.5 * widths[s];
      std::vector<std::vector<Vec2>> runs;
      for (const BgLine& part : clipped) {
        std::vector<Vec2> line;
        for (const BgPoint& p : part) line.push_back({p.x(), p.y()});
        if (line.size() < 2) continue;
        line = densified(line, step);
        std::vector<Vec2> run;
        for (std::size_t i = 0; i + 1 < line.size(); ++i) {
          BgLine segment{to_bg(line[i]), to_bg(line[i + 1])};
          const bool forbidden = avoidance && !segment_free(*avoidance, line[i], line[i + 1], half);
          const bool overlap = !forbidden && overlaps.conflict(ci, c.shape, segment, half);
          any_forbidden = any_forbidden || forbidden;
          any_overlap = any_overlap || overlap;
          if (!forbidden && !overlap) {
            if (run.empty()) run.push_back(line[i]);
            run.push_back(line[i + 1]);
          } else {
            if (run.size() >= 2) runs.push_back(std::move(run));
            run.clear();
          }
        }
        if (run.size() >= 2) runs.push_back(std::move(run));
      }
      for (auto& run : runs) {
        double run_length = 0.0;
        for (std::size_t i = 1; i < run.size(); ++i) run_length += distance(run[i - 1], run[i]);
        if (run_length < 2.0 * half) continue;
        for (std::size_t i = 0; i + 1 < run.size(); ++i) {
          overlaps.add({ci, c.shape, true, {}, BgLine{to_bg(run[i]), to_bg(run[i + 1])}, half});
        }
        out.strokes.push_back({std::move(run),
                               h.sketch.strokes[std::size_t(shape.strokes[s])].material, widths[s],
                               instance_index});
        kept = true;
      }
    }
    // Counted once per candidate: cut by forbidden pixels, cut by an overlap, or left out.
    out.forbidden += any_forbidden;
    out.overlapping += any_overlap;
    if (kept) {
      out.instances.push_back(instance);
    } else if (!any_forbidden && !any_overlap) {
      ++out.outside;
    }
  }
  return out;
}

}  // namespace tw::detail
