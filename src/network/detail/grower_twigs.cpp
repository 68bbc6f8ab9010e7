// Grower: a forest's twigs pruned where its bearings are over-represented (docs/networks.md,
// "Growth", step 11).

#include <algorithm>
#include <cmath>
#include <vector>

#include "network/detail/binned_w1.hpp"
#include "network/detail/grower.hpp"
#include "network/stats.hpp"

namespace tw::network_detail {

namespace {

// At most this share of the output's edges (as written) is pruned as twigs, in rounds of at most
// a kTwigRounds-th of that (each round's twigs chosen on one measure of the network; at most
// 4 kTwigRounds rounds), so that the pass stays near linear in the network's size.
constexpr double kTwigShare = 0.1;
constexpr int kTwigRounds = 10;

// A twig is pruned only when that brings the bearing distance (normalized W1) down by at least
// this much: no edge is taken for a gain below the measure's resolution.
constexpr double kTwigGain = 1e-4;

// The degrees' and the curvature's distances to the exemplar's may grow by this part of the
// exemplar's own half-to-half distance (its variability) as twigs are pruned, no more.
constexpr double kTwigAllowance = 0.1;

// The bearings are counted in bins of 0.1° (the W1 distance within a bin's width of the exact
// one), the degrees by their value.
constexpr int kTwigBearingBins = 1800;
constexpr int kTwigDegrees = 16;

// A twig's removal, as the network is written: its chain, and at a junction of three the two
// others, gone; their merged line (its bearing bin and curvature) in their place.
struct Twig {
  int chain = -1, leaf = -1, junction = -1;
  std::vector<int> merged_from;  // the junction's two other chains (a junction of three)
  int merged_bin = -1;           // the merged line's bearing bin (-1: none)
  double merged_curvature = -1.0;
  double bearings_after = 0.0;
};

}  // namespace

// Growth steers each branch's bearing as it is placed (Growth, step 4), but a branch's bearing is
// its stub's, and the stubs are the junctions': in a forest the output's distribution ends a few
// percent off the exemplar's, bin by bin. Twigs (edges as written from a dangling end to a
// junction) are pruned, those whose removal brings the output's bearings closest to the
// exemplar's (normalized W1) first, while that distance falls, at most kTwigShare of the edges
// are gone and the degrees and curvature stay within kTwigAllowance of the exemplar's own
// variability of where growth left them (a twig takes a dangling end and a junction's degree
// with it). A twig at a junction of three leaves its two other edges merged through it (one
// edge, bent there, instead of two); no cell is opened (a twig bounds none), no line crosses
// another.
void Grower::prune_twigs_for_bearings() {
  if (!forest_ || completing_ || exemplar_bearings_.size() < 2 || exemplar_degrees_.empty() ||
      exemplar_curvature_.empty())
    return;
  const BinnedW1 bearing_w1(exemplar_bearings_, 180.0 / kTwigBearingBins, kTwigBearingBins);
  const BinnedW1 degree_w1(exemplar_degrees_, 1.0, kTwigDegrees);
  double degrees_allowed = 0.0, curvature_allowed = 0.0;
  std::size_t budget = 0, per_round = 1;
  for (int round = 0; round < 4 * kTwigRounds; ++round) {
    const std::vector<Chain> all = chains();
    std::vector<std::vector<int>> at(out_.nodes.size());
    std::vector<int> ends(out_.nodes.size(), 0);
    std::vector<int> bearing_bin_of(all.size(), -1);
    std::vector<double> curvature_of(all.size(), -1.0);
    std::vector<double> bearings(kTwigBearingBins, 0.0), degrees(kTwigDegrees, 0.0);
    double bearing_total = 0.0, degree_total = 0.0;
    const auto curvature = [](const std::vector<Vec2>& points) {
      const double length = polyline_length(points);
      return length > 0.0 ? polyline_turning(points) / length : -1.0;
    };
    const auto chord_bin = [&](const std::vector<Vec2>& points) {
      return polyline_length(points) > 0.0 && !(points.back() == points.front())
                 ? bearing_w1.bin(chord_bearing(points.back() - points.front()))
                 : -1;
    };
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Chain& c = all[i];
      at[std::size_t(c.from)].push_back(int(i));
      if (c.to != c.from) at[std::size_t(c.to)].push_back(int(i));
      ++ends[std::size_t(c.from)], ++ends[std::size_t(c.to)];
      curvature_of[i] = curvature(c.points);
      bearing_bin_of[i] = chord_bin(c.points);
      if (bearing_bin_of[i] >= 0) bearings[std::size_t(bearing_bin_of[i])] += 1.0, ++bearing_total;
    }
    for (std::size_t n = 0; n < ends.size(); ++n)
      if (ends[n] > 0 && !out_.on_boundary[n])
        degrees[std::size_t(degree_w1.bin(ends[n]))] += 1.0, ++degree_total;
    std::vector<char> gone(all.size(), 0);
    std::vector<double> merged_curvatures;
    const auto curvature_apart = [&]() {
      std::vector<double> sample = merged_curvatures;
      for (std::size_t i = 0; i < all.size(); ++i)
        if (!gone[i] && curvature_of[i] >= 0.0) sample.push_back(curvature_of[i]);
      return sample.empty() ? 1e300 : normalized_w1(exemplar_curvature_, sample);
    };
    if (round == 0) {
      budget = std::size_t(kTwigShare * double(all.size()));
      per_round = std::max<std::size_t>(1, budget / kTwigRounds);
      degrees_allowed =
          degree_w1.apart(degrees, degree_total) + kTwigAllowance * own_degree_apart_ + 1e-12;
      curvature_allowed = curvature_apart() + kTwigAllowance * own_curvature_apart_ + 1e-12;
    }
    // A twig's removal applied to the counts (sign 1) or undone (-1).
    const auto apply = [&](const Twig& t, double sign) {
      for (int c : t.merged_from) {
        if (bearing_bin_of[std::size_t(c)] >= 0)
          bearings[std::size_t(bearing_bin_of[std::size_t(c)])] -= sign, bearing_total -= sign;
      }
      if (bearing_bin_of[std::size_t(t.chain)] >= 0)
        bearings[std::size_t(bearing_bin_of[std::size_t(t.chain)])] -= sign, bearing_total -= sign;
      if (t.merged_bin >= 0) bearings[std::size_t(t.merged_bin)] += sign, bearing_total += sign;
      degrees[1] -= sign, degree_total -= sign;  // the leaf
      const int d = degree_w1.bin(ends[std::size_t(t.junction)]);
      degrees[std::size_t(d)] -= sign;
      if (t.merged_from.empty())
        degrees[std::size_t(d - 1)] += sign;
      else
        degree_total -= sign;  // a junction of three becomes a bend, merged away
    };
    std::vector<Twig> twigs;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Chain& chain = all[i];
      if (chain.kept || chain.from == chain.to) continue;
      for (int end = 0; end < 2; ++end) {
        Twig t;
        t.chain = int(i);
        t.leaf = end == 0 ? chain.from : chain.to;
        t.junction = end == 0 ? chain.to : chain.from;
        if (ends[std::size_t(t.leaf)] != 1 || out_.on_boundary[std::size_t(t.leaf)] ||
            out_.on_boundary[std::size_t(t.junction)] || ends[std::size_t(t.junction)] < 3)
          continue;
        if (ends[std::size_t(t.junction)] == 3) {
          for (int o : at[std::size_t(t.junction)])
            if (o != int(i)) t.merged_from.push_back(o);
          if (t.merged_from.size() != 2) continue;
          const Chain &a = all[std::size_t(t.merged_from[0])],
                      &b = all[std::size_t(t.merged_from[1])];
          if (a.kept || b.kept || a.from == a.to || b.from == b.to) continue;
          std::vector<Vec2> merged = a.points;
          if (a.from == t.junction) std::reverse(merged.begin(), merged.end());
          std::vector<Vec2> rest = b.points;
          if (b.to == t.junction) std::reverse(rest.begin(), rest.end());
          merged.insert(merged.end(), rest.begin() + 1, rest.end());
          t.merged_bin = chord_bin(merged);
          t.merged_curvature = curvature(merged);
        }
        apply(t, 1.0);
        t.bearings_after = bearing_w1.apart(bearings, bearing_total);
        const bool degrees_kept = degree_w1.apart(degrees, degree_total) <= degrees_allowed;
        apply(t, -1.0);
        if (degrees_kept) twigs.push_back(std::move(t));
      }
    }
    std::stable_sort(twigs.begin(), twigs.end(), [](const Twig& a, const Twig& b) {
      return a.bearings_after < b.bearings_after;
    });
    // This round's twigs, best first, each on the counts with those before it taken off: none
    // sharing a junction or an edge with another.
    double now = bearing_w1.apart(bearings, bearing_total);
    std::vector<char> node_used(out_.nodes.size(), 0);
    std::vector<int> taken;
    for (const Twig& t : twigs) {
      if (taken.size() >= per_round || budget == 0) break;
      if (t.bearings_after >= now - kTwigGain) break;
      if (gone[std::size_t(t.chain)] || node_used[std::size_t(t.junction)] ||
          std::any_of(t.merged_from.begin(), t.merged_from.end(),
                      [&](int c) { return gone[std::size_t(c)] != 0; }))
        continue;
      apply(t, 1.0);
      const double after = bearing_w1.apart(bearings, bearing_total);
      gone[std::size_t(t.chain)] = 1;
      for (int c : t.merged_from) gone[std::size_t(c)] = 1;
      if (t.merged_curvature >= 0.0) merged_curvatures.push_back(t.merged_curvature);
      if (after < now - kTwigGain && degree_w1.apart(degrees, degree_total) <= degrees_allowed &&
          curvature_apart() <= curvature_allowed) {
        now = after;
        node_used[std::size_t(t.junction)] = 1;
        for (int c : t.merged_from) {
          const Chain& other = all[std::size_t(c)];
          node_used[std::size_t(other.from)] = node_used[std::size_t(other.to)] = 1;
        }
        taken.push_back(t.chain);
        --budget;
        continue;
      }
      apply(t, -1.0);
      gone[std::size_t(t.chain)] = 0;
      for (int c : t.merged_from) gone[std::size_t(c)] = 0;
      if (t.merged_curvature >= 0.0) merged_curvatures.pop_back();
    }
    if (taken.empty()) return;
    for (int c : taken) take_off(all[std::size_t(c)]);
  }
}

}  // namespace tw::network_detail
