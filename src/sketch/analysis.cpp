// Fine-to-coarse analysis (Olivier, Memari & Cani, Section 4). Where the paper leaves a choice
// open, docs/shape-patterns.md says what this implementation does.
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include "sketch/detail/clustering.hpp"
#include "sketch/hierarchy.hpp"

namespace tw {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgLine = bg::model::linestring<BgPoint>;

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smallest index is the root
  }
};

// Groups of indices by label, in order of first appearance.
std::vector<std::vector<int>> groups_of(const std::vector<int>& labels) {
  std::vector<std::vector<int>> groups;
  std::map<int, std::size_t> slot;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    auto [it, added] = slot.try_emplace(labels[i], groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(int(i));
  }
  return groups;
}

BgLine to_boost(const Stroke& stroke) {
  BgLine line;
  for (Vec2 p : stroke.points) line.emplace_back(p.x, p.y);
  return line;
}

std::vector<Vec2> corners(const OrientedBox& box) {
  const Vec2 a = box.axis * box.half_length, b = perp(box.axis) * box.half_width;
  return {box.center - a - b, box.center + a - b, box.center + a + b, box.center - a + b};
}

Interval project(const std::vector<Vec2>& points, Vec2 origin, Vec2 direction) {
  Interval out{INFINITY, -INFINITY};
  for (Vec2 p : points) {
    const double t = dot(p - origin, direction);
    out.lo = std::min(out.lo, t), out.hi = std::max(out.hi, t);
  }
  return out;
}

// The width of the unit input space along a unit direction: the period of a structure repeated
// on its torus, seen along that direction.
double period_along(Vec2 direction) {
  return std::abs(direction.x) + std::abs(direction.y);
}

double border_distance(Vec2 p) {
  return std::min({p.x, 1.0 - p.x, p.y, 1.0 - p.y});
}

UnboundedCategory classify_unbounded(const Stroke& stroke) {
  const OrientedBox box = detail::principal_box(stroke.points, 0.0);
  if (box.half_width <= 0.02 * box.half_length) {
    const bool both_ends = border_distance(stroke.points.front()) < 0.02 &&
                           border_distance(stroke.points.back()) < 0.02;
    return both_ends ? UnboundedCategory::line : UnboundedCategory::ray;
  }
  // Extrema of the offset across the principal axis, in stroke order.
  const Vec2 normal = perp(box.axis);
  int extrema = 0, last_sign = 0;
  for (std::size_t i = 1; i < stroke.points.size(); ++i) {
    const double dy = dot(stroke.points[i] - stroke.points[i - 1], normal);
    if (std::abs(dy) < 1e-4) continue;
    const int sign = dy > 0 ? 1 : -1;
    if (last_sign != 0 && sign != last_sign) ++extrema;
    last_sign = sign;
  }
  return extrema >= 2 ? UnboundedCategory::curve : UnboundedCategory::arc;
}

std::vector<Vec2> stroke_points(const Sketch& sketch, const SketchShape& shape) {
  std::vector<Vec2> points;
  for (int s : shape.strokes) {
    const auto& p = sketch.strokes[std::size_t(s)].points;
    points.insert(points.end(), p.begin(), p.end());
  }
  return points;
}

// Level 0: bounded strokes closer than group_distance (surface to surface) form one shape;
// every unbounded stroke is a shape of its own.
std::vector<SketchShape> find_shapes(const Sketch& sketch, const AnalysisParams& params) {
  const std::size_t n = sketch.strokes.size();
  std::vector<BgLine> lines;
  for (const Stroke& s : sketch.strokes) lines.push_back(to_boost(s));
  UnionFind groups(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Stroke &a = sketch.strokes[i], &b = sketch.strokes[j];
      if (a.unbounded || b.unbounded) continue;
      const double gap = bg::distance(lines[i], lines[j]) - 0.5 * (a.thickness + b.thickness);
      if (gap < params.group_distance) groups.join(int(i), int(j));
    }
  }
  std::vector<SketchShape> shapes;
  std::map<int, std::size_t> shape_of_root;
  for (std::size_t i = 0; i < n; ++i) {
    const Stroke& stroke = sketch.strokes[i];
    if (stroke.unbounded) {
      SketchShape& shape = shapes.emplace_back();
      shape.strokes = {int(i)};
      shape.support = ShapeSupport::fibre;
      shape.category = classify_unbounded(stroke);
      continue;
    }
    auto [it, added] = shape_of_root.try_emplace(groups.find(int(i)), shapes.size());
    if (added) shapes.emplace_back();
    shapes[it->second].strokes.push_back(int(i));
  }
  for (SketchShape& shape : shapes) {
    double pad = 0.0;
    for (int s : shape.strokes) pad = std::max(pad, 0.5 * sketch.strokes[std::size_t(s)].thickness);
    shape.box = detail::principal_box(stroke_points(sketch, shape), pad);
    if (shape.support != ShapeSupport::fibre) {
      shape.support = shape.box.half_length > params.anisotropy * shape.box.half_width
                          ? ShapeSupport::segment
                          : ShapeSupport::point;
    }
  }
  return shapes;
}

Fibre make_fibre(const std::vector<SketchShape>& shapes, std::vector<int> members, Vec2 point,
                 Vec2 direction, bool unbounded) {
  Fibre fibre;
  fibre.line = {point, direction};
  fibre.unbounded = unbounded;
  std::sort(members.begin(), members.end(), [&](int a, int b) {
    const double ta = dot(shapes[std::size_t(a)].box.center, direction);
    const double tb = dot(shapes[std::size_t(b)].box.center, direction);
    return ta != tb ? ta < tb : a < b;
  });
  fibre.shapes = members;
  std::vector<Vec2> content;
  for (int s : members) {
    const auto c = corners(shapes[std::size_t(s)].box);
    content.insert(content.end(), c.begin(), c.end());
    fibre.along.push_back(project(c, point, direction));
  }
  fibre.extent = project(content, point, perp(direction));
  if (!unbounded) {
    for (std::size_t k = 0; k + 1 < fibre.along.size(); ++k) {
      fibre.gaps_along.push_back(std::max(0.0, fibre.along[k + 1].lo - fibre.along[k].hi));
    }
    const double wrap = period_along(direction) - (fibre.along.back().hi - fibre.along.front().lo);
    fibre.gaps_along.push_back(std::max(0.0, wrap));
  }
  return fibre;
}

Vec2 mean_of(const std::vector<Vec2>& points) {
  Vec2 sum;
  for (Vec2 p : points) sum += p;
  return sum / double(points.size());
}

// Level 1 for bounded shapes of one support kind: clusters by orientation, then by offset
// across the cluster's mean direction (mean shift both times).
void bounded_fibres(const std::vector<SketchShape>& shapes, ShapeSupport support,
                    const AnalysisParams& params, std::vector<Fibre>& fibres) {
  std::vector<int> members;
  for (std::size_t i = 0; i < shapes.size(); ++i)
    if (shapes[i].support == support) members.push_back(int(i));
  if (members.empty()) return;
  std::vector<Vec2> centres;
  for (int m : members) centres.push_back(shapes[std::size_t(m)].box.center);
  // Orientation clusters: of the segments' axes, or (points) of the nearest-neighbour vectors,
  // keeping the most populated one: the alignment the points line up along.
  std::vector<std::vector<int>> by_angle;  // indices into members
  std::vector<double> cluster_angle;
  double offset_bandwidth = params.offset_bandwidth;
  if (support == ShapeSupport::segment) {
    std::vector<double> angles;
    for (int m : members) angles.push_back(line_angle(shapes[std::size_t(m)].box.axis));
    by_angle = groups_of(detail::mean_shift_axial(angles, params.angle_bandwidth));
    for (const auto& g : by_angle) {
      std::vector<double> a;
      for (int k : g) a.push_back(angles[std::size_t(k)]);
      cluster_angle.push_back(detail::axial_mean(a));
    }
  } else {
    std::vector<int> all(members.size());
    std::iota(all.begin(), all.end(), 0);
    by_angle = {all};
    double angle = 0.0;
    if (members.size() >= 2) {
      const auto nn = detail::nearest_neighbour_vectors(centres);
      std::vector<double> angles, lengths;
      for (Vec2 v : nn) angles.push_back(line_angle(v)), lengths.push_back(length(v));
      const auto clusters = groups_of(detail::mean_shift_axial(angles, params.angle_bandwidth));
      const auto largest = std::max_element(clusters.begin(), clusters.end(), [](auto& a, auto& b) {
        return a.size() < b.size();  // first of the largest wins: deterministic
      });
      std::vector<double> a;
      for (int k : *largest) a.push_back(angles[std::size_t(k)]);
      angle = detail::axial_mean(a);
      std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
      offset_bandwidth = std::min(offset_bandwidth, 0.5 * lengths[lengths.size() / 2]);
    }
    cluster_angle = {angle};
  }
  for (std::size_t g = 0; g < by_angle.size(); ++g) {
    const Vec2 direction = detail::direction_of(cluster_angle[g]);
    std::vector<double> offsets;
    for (int k : by_angle[g]) offsets.push_back(dot(centres[std::size_t(k)], perp(direction)));
    for (const auto& row : groups_of(detail::mean_shift_1d(offsets, offset_bandwidth))) {
      std::vector<int> fibre_shapes;
      std::vector<Vec2> row_centres;
      for (int r : row) {
        const int k = by_angle[g][std::size_t(r)];
        fibre_shapes.push_back(members[std::size_t(k)]);
        row_centres.push_back(centres[std::size_t(k)]);
      }
      Vec2 row_direction = direction;
      if (support == ShapeSupport::point && row_centres.size() >= 3) {
        const OrientedBox spread = detail::principal_box(row_centres, 0.0);
        if (spread.half_length > params.anisotropy * spread.half_width) row_direction = spread.axis;
      }
      fibres.push_back(
          make_fibre(shapes, fibre_shapes, mean_of(row_centres), row_direction, false));
    }
  }
}

std::vector<Vec2> fibre_content(const std::vector<SketchShape>& shapes, const Fibre& fibre) {
  std::vector<Vec2> content;
  for (int s : fibre.shapes) {
    const auto c = corners(shapes[std::size_t(s)].box);
    content.insert(content.end(), c.begin(), c.end());
  }
  return content;
}

// A level-2 or level-3 structure over members whose lines and contents are given.
Grouping make_grouping(const std::vector<int>& members, const std::vector<SupportLine>& lines,
                       const std::vector<std::vector<Vec2>>& contents) {
  Grouping grouping;
  std::vector<double> angles;
  std::vector<Vec2> points;
  for (int m : members) {
    angles.push_back(line_angle(lines[std::size_t(m)].direction));
    points.push_back(lines[std::size_t(m)].point);
  }
  const Vec2 direction = detail::direction_of(detail::axial_mean(angles));
  grouping.line = {mean_of(points), direction};
  grouping.angle_sd = detail::axial_sd(angles);
  std::vector<std::pair<Interval, int>> sorted;
  for (int m : members) {
    sorted.push_back({project(contents[std::size_t(m)], grouping.line.point, perp(direction)), m});
  }
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.first.lo != b.first.lo ? a.first.lo < b.first.lo : a.second < b.second;
  });
  for (const auto& [extent, m] : sorted) {
    grouping.members.push_back(m);
    grouping.extents.push_back(extent);
  }
  if (sorted.size() >= 2) {
    std::vector<double> gaps;
    for (std::size_t k = 0; k + 1 < sorted.size(); ++k) {
      gaps.push_back(std::max(0.0, sorted[k + 1].first.lo - sorted[k].first.hi));
    }
    const double wrap =
        period_along(perp(direction)) - (sorted.back().first.hi - sorted.front().first.lo);
    if (wrap >= 0.0) gaps.push_back(wrap);
    grouping.gap_min = *std::min_element(gaps.begin(), gaps.end());
    grouping.gap_max = *std::max_element(gaps.begin(), gaps.end());
  }
  return grouping;
}

}  // namespace

double line_angle(Vec2 direction) {
  double angle = std::atan2(direction.y, direction.x);
  if (angle < 0.0) angle += std::numbers::pi;
  if (angle >= std::numbers::pi) angle -= std::numbers::pi;
  return angle;
}

double perceived_distance(const SupportLine& a, const SupportLine& b) {
  double best = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 2; ++axis) {  // border lines X = c (axis 0) and Y = c (axis 1)
    const auto along = [axis](Vec2 v) { return axis == 0 ? v.x : v.y; };
    const auto other = [axis](Vec2 v) { return axis == 0 ? v.y : v.x; };
    if (std::abs(along(a.direction)) < 1e-12 || std::abs(along(b.direction)) < 1e-12) continue;
    for (double c : {0.0, 1.0}) {
      const double ta =
          other(a.point) + (c - along(a.point)) * other(a.direction) / along(a.direction);
      const double tb =
          other(b.point) + (c - along(b.point)) * other(b.direction) / along(b.direction);
      best = std::min(best, std::abs(ta - tb));
    }
  }
  return best;
}

SupportHierarchy analyze_sketch(const Sketch& sketch, const AnalysisParams& params) {
  check_sketch(sketch);
  SupportHierarchy h;
  h.sketch = sketch;
  h.shapes = find_shapes(sketch, params);

  // Level 1: unbounded shapes are fibres of their own; bounded ones line up into fibres.
  for (std::size_t i = 0; i < h.shapes.size(); ++i) {
    const SketchShape& shape = h.shapes[i];
    if (shape.support != ShapeSupport::fibre) continue;
    h.fibres.push_back(make_fibre(h.shapes, {int(i)}, shape.box.center, shape.box.axis, true));
  }
  bounded_fibres(h.shapes, ShapeSupport::segment, params, h.fibres);
  bounded_fibres(h.shapes, ShapeSupport::point, params, h.fibres);

  // Level 2: fibres of one orientation cluster whose perceived distance is small.
  std::vector<SupportLine> fibre_lines;
  std::vector<std::vector<Vec2>> fibre_contents;
  std::vector<double> fibre_angles;
  for (const Fibre& f : h.fibres) {
    fibre_lines.push_back(f.line);
    fibre_contents.push_back(fibre_content(h.shapes, f));
    fibre_angles.push_back(line_angle(f.line.direction));
  }
  for (const auto& orientation :
       groups_of(detail::mean_shift_axial(fibre_angles, params.angle_bandwidth))) {
    UnionFind close(orientation.size());
    for (std::size_t i = 0; i < orientation.size(); ++i)
      for (std::size_t j = i + 1; j < orientation.size(); ++j)
        if (perceived_distance(fibre_lines[std::size_t(orientation[i])],
                               fibre_lines[std::size_t(orientation[j])]) < params.median_distance)
          close.join(int(i), int(j));
    std::vector<int> roots;
    for (std::size_t i = 0; i < orientation.size(); ++i) roots.push_back(close.find(int(i)));
    for (const auto& group : groups_of(roots)) {
      std::vector<int> members;
      for (int g : group) members.push_back(orientation[std::size_t(g)]);
      h.medians.push_back(make_grouping(members, fibre_lines, fibre_contents));
    }
  }

  // Level 3: medians of one orientation form a lead direction.
  std::vector<SupportLine> median_lines;
  std::vector<std::vector<Vec2>> median_contents;
  std::vector<double> median_angles;
  for (const Grouping& m : h.medians) {
    median_lines.push_back(m.line);
    std::vector<Vec2> content;
    for (int f : m.members) {
      const auto& c = fibre_contents[std::size_t(f)];
      content.insert(content.end(), c.begin(), c.end());
    }
    median_contents.push_back(content);
    median_angles.push_back(line_angle(m.line.direction));
  }
  for (const auto& group :
       groups_of(detail::mean_shift_axial(median_angles, params.angle_bandwidth))) {
    h.leads.push_back(make_grouping(group, median_lines, median_contents));
  }
  return h;
}

}  // namespace tw
