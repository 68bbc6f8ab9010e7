#include "sketch/detail/area_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tw::detail {

namespace {

// A copy of one fibre median inside a lead direction: shifted across the lead by `shift`, its
// tilt bent so that it never moves more than `slack` from its place (s tanh(x tan(phi) / s)).
struct MedianCopy {
  int median = 0;
  double shift = 0.0;
  double tilt = 0.0;
  double slack = 0.0;
  double lo = 0.0, hi = 0.0;  // its content across the lead, after the shift
  bool original = false;
};

struct LeadFrame {
  Vec2 origin, along, across;
  double centre = 0.0;  // along coordinate the bend is centred on
};

Vec2 transform(const LeadFrame& f, const MedianCopy& c, Vec2 q) {
  const double t = dot(q - f.origin, f.along), y = dot(q - f.origin, f.across);
  double bend = 0.0;
  if (c.slack > 0.0 && c.tilt != 0.0) {
    bend = c.slack * std::tanh((t - f.centre) * std::tan(c.tilt) / c.slack);
  }
  return f.origin + f.along * t + f.across * (y + c.shift + bend);
}

Interval project_rect(Vec2 lo, Vec2 hi, Vec2 origin, Vec2 direction) {
  Interval out{INFINITY, -INFINITY};
  for (Vec2 p : {lo, hi, Vec2{lo.x, hi.y}, Vec2{hi.x, lo.y}}) {
    const double t = dot(p - origin, direction);
    out.lo = std::min(out.lo, t), out.hi = std::max(out.hi, t);
  }
  return out;
}

std::vector<MedianCopy> median_copies(const Grouping& lead, const std::vector<Grouping>& medians,
                                      Interval span, double jitter, SplitMix64& rng) {
  std::vector<MedianCopy> copies;
  for (std::size_t k = 0; k < lead.members.size(); ++k) {
    copies.push_back(
        {lead.members[k], 0.0, 0.0, 0.0, lead.extents[k].lo, lead.extents[k].hi, true});
  }
  // H2: a lead direction of a single median is extended, never repeated.
  if (lead.members.size() >= 2) {
    const auto clone = [&](double from, int side) {
      const std::size_t k = std::size_t(rng.next() % lead.members.size());
      const double gap = rng.uniform(lead.gap_min, std::max(lead.gap_min, lead.gap_max));
      const Interval e = lead.extents[k];
      const double tilt = jitter * medians[std::size_t(lead.members[k])].angle_sd * rng.normal();
      const double shift = side > 0 ? from + gap - e.lo : from - gap - e.hi;
      copies.push_back({lead.members[k], shift, tilt, 0.0, e.lo + shift, e.hi + shift, false});
      return side > 0 ? e.hi + shift : e.lo + shift;
    };
    for (double hi = lead.extents.back().hi; hi < span.hi;) hi = clone(hi, +1);
    for (double lo = lead.extents.front().lo; lo > span.lo;) lo = clone(lo, -1);
  }
  std::sort(copies.begin(), copies.end(), [](const MedianCopy& a, const MedianCopy& b) {
    return a.lo != b.lo ? a.lo < b.lo : a.median < b.median;
  });
  // Half the gap to the nearer neighbour: two neighbours bent towards each other still keep
  // apart (the paper bends arcs of circles for the same guarantee).
  for (std::size_t k = 0; k < copies.size(); ++k) {
    double gap = INFINITY;
    if (k > 0) gap = std::min(gap, copies[k].lo - copies[k - 1].hi);
    if (k + 1 < copies.size()) gap = std::min(gap, copies[k + 1].lo - copies[k].hi);
    copies[k].slack = std::isfinite(gap) ? std::max(0.0, 0.5 * gap) : 0.0;
  }
  return copies;
}

// Extension of an unbounded stroke along its fibre (x along, y across) over [x0, x1]:
// lines and rays straight, arcs by point reflection about their ends, curves cut at their first
// and last extrema and mirrored about the normal through them (Fig. 8).
std::vector<Vec2> extend_unbounded(std::vector<Vec2> local, UnboundedCategory category, double x0,
                                   double x1) {
  if (local.front().x > local.back().x) std::reverse(local.begin(), local.end());
  if (category == UnboundedCategory::line || category == UnboundedCategory::ray) {
    const Vec2 a = local.front(), b = local.back();
    const double slope = (b.y - a.y) / std::max(1e-12, b.x - a.x);
    if (x0 < a.x) local.insert(local.begin(), Vec2{x0, a.y + (x0 - a.x) * slope});
    if (x1 > b.x) local.push_back(Vec2{x1, b.y + (x1 - b.x) * slope});
    return local;
  }
  if (category == UnboundedCategory::curve) {
    std::vector<std::size_t> extrema;
    for (std::size_t i = 1; i + 1 < local.size(); ++i) {
      const double d0 = local[i].y - local[i - 1].y, d1 = local[i + 1].y - local[i].y;
      if (d0 * d1 < 0.0) extrema.push_back(i);
    }
    if (extrema.size() >= 2) {
      local = std::vector<Vec2>(local.begin() + long(extrema.front()),
                                local.begin() + long(extrema.back()) + 1);
    }
  }
  if (local.back().x - local.front().x < 1e-9) return local;  // nothing to repeat along x
  const bool point_reflection = category == UnboundedCategory::arc;
  const auto reflect = [&](const std::vector<Vec2>& piece, Vec2 about) {
    std::vector<Vec2> out;
    for (auto it = piece.rbegin(); it != piece.rend(); ++it) {
      out.push_back(point_reflection ? about * 2.0 - *it : Vec2{2.0 * about.x - it->x, it->y});
    }
    return out;
  };
  std::vector<Vec2> result = local;
  for (std::vector<Vec2> piece = local; result.back().x < x1;) {
    piece = reflect(piece, result.back());
    result.insert(result.end(), piece.begin() + 1, piece.end());
  }
  // reflect() returns its points in increasing x, starting (forwards) or ending (backwards) at
  // the point reflected about, which the result already holds.
  for (std::vector<Vec2> piece = local; result.front().x > x0;) {
    piece = reflect(piece, result.front());
    result.insert(result.begin(), piece.begin(), piece.end() - 1);
  }
  return result;
}

}  // namespace

void area_candidates(const SupportHierarchy& h, Vec2 lo, Vec2 hi, double jitter, bool keep_input,
                     std::uint64_t seed, const CandidateFilter& near, const CandidateVisitor& visit,
                     std::int64_t& skipped) {
  SplitMix64 rng(seed);
  for (std::size_t l = 0; l < h.leads.size(); ++l) {
    const Grouping& lead = h.leads[l];
    LeadFrame frame{lead.line.point, lead.line.direction, perp(lead.line.direction), 0.0};
    const Interval span = project_rect(lo, hi, frame.origin, frame.across);
    for (const MedianCopy& copy : median_copies(lead, h.medians, span, jitter, rng)) {
      const Grouping& median = h.medians[std::size_t(copy.median)];
      frame.centre = dot(median.line.point - frame.origin, frame.along);
      const bool exact = copy.original && keep_input;
      for (int f : median.members) {
        const Fibre& fibre = h.fibres[std::size_t(f)];
        const Vec2 u = fibre.line.direction, n = perp(u);
        const Interval reach = project_rect(lo, hi, fibre.line.point, u);
        if (fibre.unbounded) {
          const SketchShape& shape = h.shapes[std::size_t(fibre.shapes.front())];
          Candidate c{fibre.shapes.front(), int(l), true, exact, {}, {}, {}};
          for (int s : shape.strokes) {
            std::vector<Vec2> local;
            for (Vec2 q : h.sketch.strokes[std::size_t(s)].points) {
              local.push_back({dot(q - fibre.line.point, u), dot(q - fibre.line.point, n)});
            }
            std::vector<Vec2> stroke;
            for (Vec2 p : extend_unbounded(local, shape.category, reach.lo, reach.hi)) {
              stroke.push_back(transform(frame, copy, fibre.line.point + u * p.x + n * p.y));
            }
            c.strokes.push_back(std::move(stroke));
          }
          c.centre = transform(frame, copy, shape.box.center);
          c.axis = u;
          visit(std::move(c));
          continue;
        }
        // Bounded: the fibre's sequence of shapes is periodic along it (toroidal input space).
        const double period =
            fibre.along.back().hi - fibre.along.front().lo + fibre.gaps_along.back();
        if (!(period > 0.0)) continue;
        const int first = int(std::floor((reach.lo - fibre.along.back().hi) / period));
        const int last = int(std::ceil((reach.hi - fibre.along.front().lo) / period));
        for (int j = first; j <= last; ++j) {
          for (std::size_t k = 0; k < fibre.shapes.size(); ++k) {
            const int s = fibre.shapes[k];
            const SketchShape& shape = h.shapes[std::size_t(s)];
            const bool unperturbed = exact && j == 0;
            double dx = j * period, dy = 0.0;
            if (!unperturbed && jitter > 0.0) {
              const std::size_t count = fibre.shapes.size();
              const double before = fibre.gaps_along[(k + count - 1) % count];
              const double after = fibre.gaps_along[k];
              dx += jitter * 0.5 * std::min(before, after) * rng.uniform(-1.0, 1.0);
              const Interval across{
                  dot(shape.box.center - fibre.line.point, n) - shape.box.half_width,
                  dot(shape.box.center - fibre.line.point, n) + shape.box.half_width};
              const double room =
                  std::max(0.0, std::min(across.lo - fibre.extent.lo, fibre.extent.hi - across.hi));
              dy = jitter * room * rng.uniform(-1.0, 1.0);
            }
            const Vec2 offset = u * dx + n * dy;
            const Vec2 centre = transform(frame, copy, shape.box.center + offset);
            if (near && !near(centre, s)) {
              ++skipped;
              continue;
            }
            Candidate c{s, int(l), false, unperturbed, {}, {}, {}};
            for (int stroke_index : shape.strokes) {
              std::vector<Vec2> stroke;
              for (Vec2 q : h.sketch.strokes[std::size_t(stroke_index)].points) {
                stroke.push_back(transform(frame, copy, q + offset));
              }
              c.strokes.push_back(std::move(stroke));
            }
            c.centre = centre;
            c.axis = normalized(
                transform(frame, copy, shape.box.center + offset + shape.box.axis * 1e-3) -
                c.centre);
            visit(std::move(c));
          }
        }
      }
    }
  }
}

}  // namespace tw::detail
