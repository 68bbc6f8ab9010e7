#include "sketch/area_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "sketch/detail/area_candidates.hpp"
#include "sketch/detail/area_filter.hpp"
#include "sketch/detail/clustering.hpp"
#include "sketch/detail/domain_cover.hpp"
#include "sketch/detail/field_frame.hpp"

namespace tw {

namespace {

// Area centroid of the outer ring (shoelace), holes ignored: where the sketch is laid.
Vec2 centroid(const Ring& ring) {
  double area = 0.0;
  Vec2 sum;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const double w = cross(a, b);
    area += w;
    sum += (a + b) * w;
  }
  if (std::abs(area) < 1e-12) {
    Vec2 mean;
    for (Vec2 p : ring) mean += p;
    return mean / double(ring.size());
  }
  return sum / (3.0 * area);
}

// Cut granularity, test pieces and simplification of unbounded strokes (detail/area_filter.hpp).
detail::PlacementOptions placement(const AreaSynthesisParams& params, double cell) {
  detail::PlacementOptions o;
  o.scale = params.scale;
  o.step = cell > 0.0 ? 0.5 * cell : 0.01 * params.scale;
  o.piece = 32.0 * o.step;
  o.tolerance = params.tolerance > 0.0 ? params.tolerance : 0.5 * o.step;
  return o;
}

// Candidates streamed into the placer, those far from the polygon skipped unbuilt.
AreaPattern place_all(const SupportHierarchy& h, const Polygon& domain, Vec2 lo, Vec2 hi,
                      const AreaSynthesisParams& params, const std::function<Vec2(Vec2)>& to_world,
                      const SparseAvoidance* avoidance, double densify) {
  detail::PlacementOptions options =
      placement(params, avoidance ? avoidance->grid.pixel_width : 0.0);
  options.densify = densify;
  const detail::DomainCover cover(domain, params.scale / 8.0);
  // A shape's reach from its centre, in metres (twice its box's half diagonal: a curved frame
  // may stretch it).
  std::vector<double> reach;
  for (const SketchShape& shape : h.shapes)
    reach.push_back(2.0 * std::hypot(shape.box.half_length, shape.box.half_width) * params.scale);
  detail::Placer placer(h, domain, cover, to_world, avoidance, options);
  std::int64_t skipped = 0;
  detail::area_candidates(
      h, lo, hi, params.jitter, params.keep_input, params.seed,
      [&](Vec2 centre, int shape) {
        return cover.near(to_world(centre), reach[std::size_t(shape)]);
      },
      [&](detail::Candidate&& c) { placer.place(c); }, skipped);
  AreaPattern out = placer.take();
  out.outside +=
      int(std::min<std::int64_t>(skipped, std::numeric_limits<int>::max() - out.outside));
  return out;
}

}  // namespace

double polygon_area(const Polygon& polygon) {
  double area = 0.0;
  for (std::size_t r = 0; r < polygon.size(); ++r) {
    double twice = 0.0;
    const Ring& ring = polygon[r];
    for (std::size_t i = 0; i < ring.size(); ++i)
      twice += cross(ring[i], ring[(i + 1) % ring.size()]);
    area += (r == 0 ? 0.5 : -0.5) * std::abs(twice);
  }
  return area;
}

AreaEstimate estimate_area(const SupportHierarchy& h, const Polygon& domain,
                           const AreaSynthesisParams& params, double cell) {
  const detail::PlacementOptions o = placement(params, cell);
  const double squares = polygon_area(domain) / (params.scale * params.scale);
  AreaEstimate e;
  for (const SketchShape& shape : h.shapes) {
    if (shape.support == ShapeSupport::fibre) {
      // A stroke across the square repeats once per square along it: its length per square
      // metre is its sketch length / scale per sketch square.
      double length = 0.0;
      const auto& points = h.sketch.strokes[std::size_t(shape.strokes.front())].points;
      for (std::size_t i = 1; i < points.size(); ++i) length += distance(points[i - 1], points[i]);
      const double pieces = squares * length * params.scale / o.piece;
      e.shapes += pieces;
      e.bytes += pieces * 160.0;  // an R-tree entry and its piece
      continue;
    }
    // An instance, its strokes and points, its box in the R-tree.
    double points = 0.0;
    for (int s : shape.strokes) points += double(h.sketch.strokes[std::size_t(s)].points.size());
    e.shapes += squares;
    e.bytes += squares * (320.0 + 96.0 * double(shape.strokes.size()) + 16.0 * points);
  }
  return e;
}

Vec2 area_anchor(const Polygon& domain) {
  if (domain.empty() || domain.front().size() < 3) fail("area: the polygon has no outer ring");
  return centroid(domain.front());
}

double long_axis_bearing(const Polygon& domain) {
  if (domain.empty() || domain.front().size() < 3) fail("area: the polygon has no outer ring");
  // Points every 1/64 of the perimeter, so a densely digitized side does not pull the axis.
  const Ring& ring = domain.front();
  double perimeter = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    perimeter += distance(ring[i], ring[(i + 1) % ring.size()]);
  std::vector<Vec2> samples;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const int n = std::max(1, int(std::ceil(64.0 * distance(a, b) / perimeter)));
    for (int k = 0; k < n; ++k) samples.push_back(lerp(a, b, double(k) / n));
  }
  return line_angle(detail::principal_box(samples, 0.0).axis);
}

AreaPattern synthesize_area(const SupportHierarchy& hierarchy, const Polygon& domain,
                            const AreaSynthesisParams& params, const SparseAvoidance* avoidance) {
  if (domain.empty() || domain.front().size() < 3) fail("area: the polygon has no outer ring");
  if (!(params.scale > 0.0) || !std::isfinite(params.scale)) {
    fail("area: scale must be > 0 metres per sketch unit, got {}", params.scale);
  }
  if (!(params.jitter >= 0.0 && params.jitter <= 1.0)) {
    fail("area: jitter must be in [0, 1], got {}", params.jitter);
  }
  const Vec2 anchor = centroid(domain.front());
  if (params.lead_field) {
    // Rows along the field: input space (q - centre) * scale is the frame's (u, v).
    Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    double reach = 0.0;
    for (Vec2 p : domain.front()) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      reach = std::max(reach, distance(p, anchor));
    }
    reach += 0.5 * params.scale;  // curves bend: the frame reaches past the polygon
    const double step =
        params.lead_step > 0.0 ? params.lead_step : std::max(params.scale / 16.0, reach / 512.0);
    const detail::FieldFrame frame(anchor, params.bearing, params.lead_field, reach, step);
    Vec2 uv_lo, uv_hi;
    frame.extent_within(lo, hi, uv_lo, uv_hi);
    const auto to_world = [&](Vec2 q) {
      return frame.to_world((q - Vec2{0.5, 0.5}) * params.scale);
    };
    return place_all(hierarchy, domain, Vec2{0.5, 0.5} + uv_lo / params.scale,
                     Vec2{0.5, 0.5} + uv_hi / params.scale, params, to_world, avoidance,
                     step / params.scale);
  }
  const auto to_world = [&](Vec2 q) {
    return anchor + rotated((q - Vec2{0.5, 0.5}) * params.scale, params.bearing);
  };
  const auto to_sketch = [&](Vec2 w) {
    return Vec2{0.5, 0.5} + rotated(w - anchor, -params.bearing) / params.scale;
  };
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : domain.front()) {
    const Vec2 q = to_sketch(p);
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
  }
  return place_all(hierarchy, domain, lo, hi, params, to_world, avoidance, 0.0);
}

SupportHierarchy hybridize(const SupportHierarchy& structure, const SupportHierarchy& shapes,
                           const AnalysisParams& params) {
  std::vector<int> donors;  // bounded shapes of the donor, in fibre order
  std::vector<Vec2> donor_fibre;
  for (const Fibre& f : shapes.fibres) {
    if (f.unbounded) continue;
    for (int s : f.shapes) donors.push_back(s), donor_fibre.push_back(f.line.direction);
  }
  if (donors.empty()) fail("hybridize: {} has no bounded shape to lend", shapes.sketch.source);
  Sketch sketch;
  sketch.source = structure.sketch.source + " + " + shapes.sketch.source;
  for (const Stroke& s : structure.sketch.strokes)
    if (s.unbounded) sketch.strokes.push_back(s);
  std::size_t next = 0;
  for (const Fibre& f : structure.fibres) {
    if (f.unbounded) continue;
    for (std::size_t k = 0; k < f.shapes.size(); ++k) {
      const OrientedBox& slot = structure.shapes[std::size_t(f.shapes[k])].box;
      const std::size_t d = next++ % donors.size();
      const SketchShape& donor = shapes.shapes[std::size_t(donors[d])];
      const double turn = line_angle(f.line.direction) - line_angle(donor_fibre[d]);
      // Room along the fibre: the slot and half the gap on its tighter side.
      const std::size_t count = f.shapes.size();
      const double room =
          slot.half_length + 0.5 * std::min(f.gaps_along[k], f.gaps_along[(k + count - 1) % count]);
      const double fit = std::min(1.0, room / std::max(1e-12, donor.box.half_length));
      for (int s : donor.strokes) {
        Stroke stroke = shapes.sketch.strokes[std::size_t(s)];
        for (Vec2& p : stroke.points) {
          p = slot.center + rotated((p - donor.box.center) * fit, turn);
          p = {std::clamp(p.x, 0.0, 1.0), std::clamp(p.y, 0.0, 1.0)};
        }
        stroke.thickness *= fit;
        sketch.strokes.push_back(std::move(stroke));
      }
    }
  }
  return analyze_sketch(sketch, params);
}

}  // namespace tw
