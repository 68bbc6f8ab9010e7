// Grower: a forest's twigs pruned where its bearings are over-represented (docs/networks.md,
// "Growth", step 9).

#include <algorithm>
#include <cmath>
#include <vector>

#include "network/detail/grower.hpp"
#include "network/stats.hpp"

namespace tw::network_detail {

namespace {

// At most this share of the output's edges (as written) is pruned as twigs.
constexpr double kTwigShare = 0.1;

// A twig is pruned only when that brings the bearing distance (normalized W1) down by at least
// this much: no edge is taken for a gain below the measure's resolution.
constexpr double kTwigGain = 1e-4;

// The degrees' and the curvature's distances to the exemplar's may grow by this part of the
// exemplar's own half-to-half distance (its variability) as twigs are pruned, no more.
constexpr double kTwigAllowance = 0.1;

// The samples of network_stats that a twig's removal changes, of the output as written: per edge
// its chord's bearing and its curvature, per node its degree.
struct TwigSamples {
  std::vector<double> bearing, curvature, degree;
  void add_edge(const std::vector<Vec2>& points) {
    const double length = polyline_length(points);
    if (!(length > 0.0)) return;
    curvature.push_back(polyline_turning(points) / length);
    if (!(points.back() == points.front()))
      bearing.push_back(chord_bearing(points.back() - points.front()));
  }
};

}  // namespace

// Growth steers each branch's bearing as it is placed (Growth, step 4), but a branch's bearing is
// its stub's, and the stubs are the junctions': in a forest the output's distribution ends a few
// percent off the exemplar's, bin by bin. A twig (an edge as written from a dangling end to a
// junction) is pruned, the one whose removal brings the output's bearings closest to the
// exemplar's (normalized W1), while one does, at most kTwigShare of the edges are gone and the
// degrees and curvature stay within kTwigAllowance of the exemplar's own variability of where
// growth left them (a twig takes a dangling end and a junction's degree with it). A twig at a
// junction of three leaves its two other edges merged through it (one edge, bent there, instead of
// two); no cell is opened (a twig bounds none), no line crosses another.
void Grower::prune_twigs_for_bearings() {
  if (!forest_ || completing_ || exemplar_bearings_.size() < 2) return;
  // The bearing distance, or nothing (infinite) when the degrees or the curvature are farther
  // from the exemplar's than they were as grown, beyond the allowance.
  double degrees_allowed = 0.0, curvature_allowed = 0.0;
  const auto apart = [&](const TwigSamples& s) {
    if (s.bearing.empty() || s.degree.empty() || s.curvature.empty()) return 1e300;
    if (normalized_w1(exemplar_degrees_, s.degree) > degrees_allowed ||
        normalized_w1(exemplar_curvature_, s.curvature) > curvature_allowed)
      return 1e300;
    return normalized_w1(exemplar_bearings_, s.bearing);
  };
  std::vector<Chain> all = chains();
  const std::size_t budget = std::size_t(kTwigShare * double(all.size()));
  for (std::size_t pruned = 0; pruned < budget; ++pruned) {
    if (pruned > 0) all = chains();
    std::vector<std::vector<int>> at(out_.nodes.size());
    std::vector<int> ends(out_.nodes.size(), 0);
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Chain& c = all[i];
      at[std::size_t(c.from)].push_back(int(i));
      if (c.to != c.from) at[std::size_t(c.to)].push_back(int(i));
      ++ends[std::size_t(c.from)], ++ends[std::size_t(c.to)];
    }
    // The samples without the chains in `gone` and the nodes in `gone_nodes`, with `merged`.
    const auto samples = [&](const std::vector<int>& gone, const std::vector<int>& gone_nodes,
                             const std::vector<Vec2>* merged, int lower_node) {
      TwigSamples s;
      for (std::size_t i = 0; i < all.size(); ++i)
        if (std::find(gone.begin(), gone.end(), int(i)) == gone.end()) s.add_edge(all[i].points);
      if (merged) s.add_edge(*merged);
      for (std::size_t n = 0; n < ends.size(); ++n)
        if (ends[n] > 0 && !out_.on_boundary[n] &&
            std::find(gone_nodes.begin(), gone_nodes.end(), int(n)) == gone_nodes.end())
          s.degree.push_back(double(ends[n] - (int(n) == lower_node)));
      return s;
    };
    if (pruned == 0) {
      const TwigSamples grown = samples({}, {}, nullptr, -1);
      if (grown.degree.empty() || grown.curvature.empty()) return;
      degrees_allowed = normalized_w1(exemplar_degrees_, grown.degree) +
                        kTwigAllowance * own_degree_apart_ + 1e-12;
      curvature_allowed = normalized_w1(exemplar_curvature_, grown.curvature) +
                          kTwigAllowance * own_curvature_apart_ + 1e-12;
    }
    double best = apart(samples({}, {}, nullptr, -1)) - kTwigGain;
    int best_twig = -1;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Chain& twig = all[i];
      if (twig.kept || twig.from == twig.to) continue;
      for (int end = 0; end < 2; ++end) {
        const int leaf = end == 0 ? twig.from : twig.to, junction = end == 0 ? twig.to : twig.from;
        if (ends[std::size_t(leaf)] != 1 || out_.on_boundary[std::size_t(leaf)] ||
            ends[std::size_t(junction)] < 3)
          continue;
        double d = 0.0;
        if (ends[std::size_t(junction)] == 3) {
          // The two others become one edge through the junction, as the network is written.
          std::vector<int> others;
          for (int o : at[std::size_t(junction)])
            if (o != int(i)) others.push_back(o);
          if (others.size() != 2) continue;
          const Chain &a = all[std::size_t(others[0])], &b = all[std::size_t(others[1])];
          if (a.kept || b.kept || a.from == a.to || b.from == b.to) continue;
          std::vector<Vec2> merged = a.points;
          if (a.from == junction) std::reverse(merged.begin(), merged.end());
          std::vector<Vec2> rest = b.points;
          if (b.to == junction) std::reverse(rest.begin(), rest.end());
          merged.insert(merged.end(), rest.begin() + 1, rest.end());
          d = apart(samples({int(i), others[0], others[1]}, {leaf, junction}, &merged, -1));
        } else {
          d = apart(samples({int(i)}, {leaf}, nullptr, junction));
        }
        if (d < best) best = d, best_twig = int(i);
      }
    }
    if (best_twig < 0) return;
    take_off(all[std::size_t(best_twig)]);
  }
}

}  // namespace tw::network_detail
