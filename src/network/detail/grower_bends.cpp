// Grower: the bends left in a straight exemplar's output eased to turn per metre as the
// exemplar's own bends do (docs/networks.md, "Growth" 12).

#include <algorithm>
#include <optional>
#include <vector>

#include "network/detail/grower.hpp"

namespace tw::network_detail {

namespace {

// The easing is searched on this many even steps from the line to its chord, then refined by
// halving within the step found this many times.
constexpr int kEaseGridSteps = 20;
constexpr int kEaseHalvings = 12;

// Eased lines tried per bend: turning per metre as the exemplar's bends do on average, then
// evenly less eased up to as its sharpest bend turns, until one is committed.
constexpr int kEaseTries = 4;

// Line p with every point moved towards the chord p.front()-p.back() by share t of its distance
// from it (the ends stay): at t = 1 the chord, a bend of one corner turning less as t grows.
std::vector<Vec2> eased_towards_chord(const std::vector<Vec2>& p, double t) {
  const Vec2 a = p.front(), chord = p.back() - p.front();
  const double chord_sq = chord.x * chord.x + chord.y * chord.y;
  std::vector<Vec2> out = p;
  if (chord_sq <= 0.0) return out;
  for (std::size_t k = 1; k + 1 < p.size(); ++k) {
    const Vec2 d = p[k] - a;
    const Vec2 foot = a + chord * ((d.x * chord.x + d.y * chord.y) / chord_sq);
    out[k] = p[k] + (foot - p[k]) * t;
  }
  return out;
}

double turning_per_metre(const std::vector<Vec2>& p) {
  const double length = polyline_length(p);
  return length > 0.0 ? polyline_turning(p) / length : 0.0;
}

// The least easing (share t) whose line turns at most `target` per metre, or none (a line bent
// back on itself, as a U, turns as much whatever its depth).
std::optional<double> easing_for(const std::vector<Vec2>& p, double target) {
  double below = 0.0;
  for (int step = 1; step < kEaseGridSteps; ++step) {
    double above = double(step) / kEaseGridSteps;
    if (turning_per_metre(eased_towards_chord(p, above)) > target) {
      below = above;
      continue;
    }
    for (int k = 0; k < kEaseHalvings; ++k) {
      const double mid = 0.5 * (below + above);
      (turning_per_metre(eased_towards_chord(p, mid)) > target ? below : above) = mid;
    }
    return above;
  }
  return std::nullopt;
}

}  // namespace

// Where the exemplar's edges are nearly all straight, its few bent ones (a frame's corners) turn
// a measured amount per metre, and the output's bends left by straighten_edges (corners no chord,
// removal or link could undo, kinks whose chord was refused) are in its curvature distribution
// beside them: one turning more per metre than the exemplar's sharpest bend is eased towards its
// chord until it turns as the exemplar's bends do on average (else, that line refused, less far,
// up to as its sharpest does), when the eased line leaves its junctions within
// kStraightenDeflection of its old headings, meets the lines there at kMinMeetingAngle or more
// and is committed under the rules of every line. A bend is kept, not straightened: the
// exemplar's share of bent edges is straighten_edges' business.
void Grower::ease_sharp_bends() {
  if (straight_share_ < kStraightShare || bend_curvature_max_ <= 0.0) return;
  for (const Chain& c : chains()) {
    if (c.kept || c.from == c.to || on_border(c) || !still_a_chain(c)) continue;
    const double turning = polyline_turning(c.points);
    if (turning >= kStraightTurning && turning_per_metre(c.points) > bend_curvature_max_) ease(c);
  }
}

bool Grower::ease(const Chain& c) {
  for (int k = 0; k < kEaseTries; ++k) {
    const double target = bend_curvature_mean_ + (bend_curvature_max_ - bend_curvature_mean_) *
                                                     double(k) / double(kEaseTries - 1);
    const std::optional<double> t = easing_for(c.points, target);
    if (!t) return false;
    const std::vector<Vec2> line = eased_towards_chord(c.points, *t);
    if (ends_meet_lines(c, line, kMinMeetingAngle) && replace_chain(c, line)) return true;
  }
  return false;
}

}  // namespace tw::network_detail
