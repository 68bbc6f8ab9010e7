#include "sketch/detail/area_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/boost_geometry.hpp"
#include "core/segment_distance.hpp"

namespace tw::detail {

using namespace geometry;

namespace {

using geometry::to_bg;  // and the overloads below, for this file's shapes

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

BgPolygon to_bg(const std::array<Vec2, 4>& corners) {
  BgPolygon box;
  for (Vec2 p : corners) box.outer().push_back(to_bg(p));
  bg::correct(box);
  return box;
}

// The oriented box of points along `axis`, padded.
std::array<Vec2, 4> oriented_box(const std::vector<std::vector<Vec2>>& strokes, Vec2 axis,
                                 double pad) {
  const Vec2 normal = perp(axis);
  double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
  for (const auto& s : strokes)
    for (Vec2 p : s) {
      a0 = std::min(a0, dot(p, axis)), a1 = std::max(a1, dot(p, axis));
      b0 = std::min(b0, dot(p, normal)), b1 = std::max(b1, dot(p, normal));
    }
  a0 -= pad, a1 += pad, b0 -= pad, b1 += pad;
  return {axis * a0 + normal * b0, axis * a1 + normal * b0, axis * a1 + normal * b1,
          axis * a0 + normal * b1};
}

// What is placed: a bounded shape's box (4 corners) or one piece of an unbounded stroke (the
// first two). Compact: a canton of furrows holds millions.
struct Placed {
  std::uint32_t candidate = 0;
  int shape = 0;
  float half_width = 0.0f;
  bool unbounded = false;
  std::array<Vec2, 4> points;
};
using Tree = bgi::rtree<std::pair<BgBox, std::uint32_t>, bgi::rstar<16>>;

BgBox bounds_of(const Placed& p) {
  const int n = p.unbounded ? 2 : 4;
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (int i = 0; i < n; ++i) {
    lo = {std::min(lo.x, p.points[i].x), std::min(lo.y, p.points[i].y)};
    hi = {std::max(hi.x, p.points[i].x), std::max(hi.y, p.points[i].y)};
  }
  return {to_bg(lo), to_bg(hi)};
}

class Overlaps {
 public:
  explicit Overlaps(const SupportHierarchy& h) : h_(h) {}

  // True when `shape`'s geometry meets a placed shape that it was disjoint from in the sketch.
  template <class Geometry>
  bool conflict(std::uint32_t candidate, int shape, const Geometry& geometry, double half_width) {
    BgBox bounds;
    bg::envelope(geometry, bounds);
    const double m = half_width + max_half_width_;
    BgBox query(BgPoint(bounds.min_corner().x() - m, bounds.min_corner().y() - m),
                BgPoint(bounds.max_corner().x() + m, bounds.max_corner().y() + m));
    hits_.clear();
    tree_.query(bgi::intersects(query), std::back_inserter(hits_));
    std::sort(hits_.begin(), hits_.end(), [](auto& a, auto& b) { return a.second < b.second; });
    for (const auto& [box, index] : hits_) {
      const Placed& other = placed_[index];
      if (other.candidate == candidate || overlapped_in_sketch(shape, other.shape)) continue;
      const double d = other.unbounded
                           ? double(bg::distance(
                                 geometry, BgLine{to_bg(other.points[0]), to_bg(other.points[1])}))
                           : double(bg::distance(geometry, to_bg(other.points)));
      if (d <= half_width + other.half_width) return true;
    }
    return false;
  }

  void add(const Placed& placed) {
    max_half_width_ = std::max(max_half_width_, double(placed.half_width));
    tree_.insert({bounds_of(placed), std::uint32_t(placed_.size())});
    placed_.push_back(placed);
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
  std::vector<std::pair<BgBox, std::uint32_t>> hits_;
  double max_half_width_ = 0.0;
  std::map<std::pair<int, int>, bool> sketch_overlap_;
};

// Half a cell's diagonal: a stroke kept that much farther from every forbidden cell centre stays
// off the forbidden cells' squares, not only their centres (a polygon's edge is crossed by at
// most a sliver of a cell).
double cell_clearance(const SparseAvoidance& a) {
  return 0.5 * std::hypot(a.grid.pixel_width, a.grid.pixel_height);
}

// Every segment of the strokes clear of forbidden cells, tested in pieces of at most `piece`.
bool shape_clear(const SparseAvoidance& a, const std::vector<std::vector<Vec2>>& strokes,
                 const std::vector<double>& widths, double piece) {
  for (std::size_t s = 0; s < strokes.size(); ++s)
    for (std::size_t i = 0; i + 1 < strokes[s].size(); ++i) {
      const Vec2 p = strokes[s][i], q = strokes[s][i + 1];
      const int n = std::max(1, int(std::ceil(distance(p, q) / piece)));
      for (int k = 0; k < n; ++k)
        if (!segment_clear(a, lerp(p, q, double(k) / n), lerp(p, q, double(k + 1) / n),
                           0.5 * widths[s] + cell_clearance(a)))
          return false;
    }
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

// Douglas-Peucker (Boost.Geometry) within `tolerance`, ends kept. A kept segment whose
// skipped points do not all lie on it (beyond rounding) must pass `still_free`; where it does
// not, the traced points in between are kept.
template <class Test>
std::vector<Vec2> simplified(const std::vector<Vec2>& line, double tolerance, Test still_free) {
  if (line.size() <= 2 || !(tolerance > 0.0)) return line;
  BgLine out;
  bg::simplify(to_bg(line), out, tolerance);
  std::vector<Vec2> points{line.front()};
  std::size_t from = 0;  // index in `line` of points.back()
  for (std::size_t k = 1; k < out.size(); ++k) {
    const Vec2 target{out[k].x(), out[k].y()};
    std::size_t to = from + 1;
    while (to + 1 < line.size() && line[to] != target) ++to;  // simplify keeps a subsequence
    double off = 0.0;
    for (std::size_t i = from + 1; i < to; ++i)
      off = std::max(off, distance_to_segment(line[i], line[from], line[to]));
    const double rounding = 1e-9 * (1.0 + std::abs(line[from].x) + std::abs(line[from].y));
    if (off <= rounding || still_free(line[from], line[to])) {
      points.push_back(line[to]);
    } else {
      points.insert(points.end(), line.begin() + long(from) + 1, line.begin() + long(to) + 1);
    }
    from = to;
  }
  return points;
}

}  // namespace

struct Placer::State {
  explicit State(const SupportHierarchy& h, const Polygon& domain)
      : region(to_bg(domain)), overlaps(h) {}
  BgPolygon region;
  Overlaps overlaps;
};

Placer::Placer(const SupportHierarchy& h, const Polygon& domain, const DomainCover& cover,
               std::function<Vec2(Vec2)> to_world, const SparseAvoidance* avoidance,
               const PlacementOptions& options)
    : h_(h),
      cover_(cover),
      to_world_(std::move(to_world)),
      avoidance_(avoidance),
      options_(options),
      state_(std::make_unique<State>(h, domain)) {}

Placer::~Placer() = default;

void Placer::place_bounded(const Candidate& c, ShapeInstance instance,
                           std::vector<std::vector<Vec2>> strokes,
                           const std::vector<double>& widths, Vec2 axis, double half_width) {
  const SketchShape& shape = h_.shapes[std::size_t(c.shape)];
  const std::uint32_t ci = next_ - 1;
  const std::array<Vec2, 4> corners = oriented_box(strokes, axis, half_width);
  const std::optional<bool> decided = cover_.contains(corners);
  const BgPolygon box = to_bg(corners);
  if (!(decided ? *decided : bg::within(box, state_->region))) {
    ++out_.outside;
    return;
  }
  if (avoidance_ && !shape_clear(*avoidance_, strokes, widths, options_.piece)) {
    ++out_.forbidden;
    return;
  }
  if (state_->overlaps.conflict(ci, c.shape, box, 0.0)) {
    ++out_.overlapping;
    return;
  }
  state_->overlaps.add({ci, c.shape, 0.0f, false, corners});
  const int instance_index = int(out_.instances.size());
  out_.instances.push_back(std::move(instance));
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    out_.strokes.push_back({std::move(strokes[s]),
                            h_.sketch.strokes[std::size_t(shape.strokes[s])].material, widths[s],
                            instance_index});
  }
}

void Placer::place(const Candidate& c) {
  const std::uint32_t ci = next_++;
  const SketchShape& shape = h_.shapes[std::size_t(c.shape)];
  const double scale = options_.scale, densify = options_.densify;
  std::vector<std::vector<Vec2>> strokes;
  std::vector<double> widths;
  double half_width = 0.0;
  for (std::size_t s = 0; s < c.strokes.size(); ++s) {
    auto& world = strokes.emplace_back();
    for (Vec2 q : densify > 0.0 ? densified(c.strokes[s], densify) : c.strokes[s])
      world.push_back(to_world_(q));
    widths.push_back(h_.sketch.strokes[std::size_t(shape.strokes[s])].thickness * scale);
    half_width = std::max(half_width, 0.5 * widths.back());
  }
  const Vec2 centre = to_world_(c.centre);
  // The axis's image over one input unit when affine; over `densify` when curved.
  const Vec2 axis =
      normalized(to_world_(c.centre + c.axis * (densify > 0.0 ? densify : 1.0)) - centre);
  ShapeInstance instance{c.shape,    c.lead,
                         centre,     std::atan2(axis.y, axis.x),
                         scale,      h_.sketch.strokes[std::size_t(shape.strokes.front())].material,
                         c.unbounded};
  if (!c.unbounded) {
    place_bounded(c, std::move(instance), std::move(strokes), widths, axis, half_width);
    return;
  }
  // Unbounded: clipped to the polygon, then cut where a piece is forbidden or meets a shape it
  // was disjoint from (pieces bisected down to `step` where blocked); runs shorter than the
  // stroke's width are dropped, the others simplified within `tolerance`. A simplified segment
  // that leaves the run's line is tested again, and where it fails the run keeps its traced
  // points there: what is written, and goes into the R-tree, is what was tested.
  const double tolerance = options_.tolerance, step = options_.step;
  const int instance_index = int(out_.instances.size());
  bool kept = false, any_forbidden = false, any_overlap = false;
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    BgLines clipped;
    bg::intersection(to_bg(strokes[s]), state_->region, clipped);
    const double half = 0.5 * widths[s];
    struct Run {
      std::vector<Vec2> points;
    };
    std::vector<Run> runs;
    Run run;
    const auto close_run = [&] {
      if (run.points.size() >= 2) runs.push_back(std::move(run));
      run = Run{};
    };
    const auto free = [&](Vec2 a, Vec2 b, bool finest) {
      const bool forbidden =
          avoidance_ && !segment_clear(*avoidance_, a, b, half + cell_clearance(*avoidance_));
      const bool overlap =
          !forbidden && state_->overlaps.conflict(ci, c.shape, BgLine{to_bg(a), to_bg(b)}, half);
      if (finest) {
        any_forbidden = any_forbidden || forbidden;
        any_overlap = any_overlap || overlap;
      }
      return !forbidden && !overlap;
    };
    const auto walk = [&](auto&& self, Vec2 a, Vec2 b) -> void {
      const bool finest = distance(a, b) <= step;
      if (free(a, b, finest)) {
        if (run.points.empty()) run.points.push_back(a);
        run.points.push_back(b);
        return;
      }
      if (finest) {
        close_run();
        return;
      }
      const Vec2 mid = lerp(a, b, 0.5);
      self(self, a, mid);
      self(self, mid, b);
    };
    for (const BgLine& part : clipped) {
      if (part.size() < 2) continue;
      for (std::size_t i = 0; i + 1 < part.size(); ++i) {
        const Vec2 p{part[i].x(), part[i].y()}, q{part[i + 1].x(), part[i + 1].y()};
        const int n = std::max(1, int(std::ceil(distance(p, q) / options_.piece)));
        for (int k = 0; k < n; ++k)
          walk(walk, lerp(p, q, double(k) / n), lerp(p, q, double(k + 1) / n));
      }
      close_run();
    }
    for (Run& r : runs) {
      double run_length = 0.0;
      for (std::size_t i = 1; i < r.points.size(); ++i)
        run_length += distance(r.points[i - 1], r.points[i]);
      if (run_length < 2.0 * half) continue;
      std::vector<Vec2> written = simplified(r.points, tolerance, [&](Vec2 a, Vec2 b) {
        const int n = std::max(1, int(std::ceil(distance(a, b) / options_.piece)));
        for (int k = 0; k < n; ++k)
          if (!free(lerp(a, b, double(k) / n), lerp(a, b, double(k + 1) / n), false)) return false;
        return true;
      });
      // Into the R-tree in pieces: long segments would make boxes that every query meets.
      for (std::size_t i = 0; i + 1 < written.size(); ++i) {
        const Vec2 a = written[i], b = written[i + 1];
        const int n = std::max(1, int(std::ceil(distance(a, b) / options_.piece)));
        for (int k = 0; k < n; ++k) {
          const Vec2 p = lerp(a, b, double(k) / n), q = lerp(a, b, double(k + 1) / n);
          state_->overlaps.add({ci, c.shape, float(half), true, {p, q, Vec2{}, Vec2{}}});
        }
      }
      out_.strokes.push_back({std::move(written),
                              h_.sketch.strokes[std::size_t(shape.strokes[s])].material, widths[s],
                              instance_index});
      kept = true;
    }
  }
  // Counted once per candidate: cut by forbidden cells, cut by an overlap, or left out.
  out_.forbidden += any_forbidden;
  out_.overlapping += any_overlap;
  if (kept) {
    out_.instances.push_back(std::move(instance));
  } else if (!any_forbidden && !any_overlap) {
    ++out_.outside;
  }
}

}  // namespace tw::detail
