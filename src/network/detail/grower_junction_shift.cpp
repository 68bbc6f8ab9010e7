// Grower: the junctions of a network of closed bent cells, or of a forest, shifted a little where
// that brings the output's edge bearings nearer the exemplar's (docs/networks.md, "Growth",
// step 13).

#include <algorithm>
#include <cmath>
#include <vector>

#include "network/detail/binned_w1.hpp"
#include "network/detail/grower.hpp"
#include "network/stats.hpp"

namespace tw::network_detail {

namespace {

// A junction moves by one of these parts of the median edge length, in one of kShiftDirections
// directions: a few degrees of its edges' chords, well within the exemplar's own wobble.
constexpr double kShiftSteps[] = {0.04, 0.08};
constexpr int kShiftDirections = 8;

// At most this many rounds, each moving junctions that share no edge, best gain first, at most
// kShiftShare of the junctions in all; the pass ends after a round that gains less than
// kShiftLastGain of the first round's (each round finds the chains and tries every junction:
// over six times the counties' side, 15 000 edges, 8 rounds took 5 s where the quilt takes 1.5).
constexpr int kShiftRounds = 8;
constexpr double kShiftShare = 0.5;
constexpr double kShiftLastGain = 0.1;

// A move is made only when it brings the bearing distance (normalized W1) down by at least as
// much as one edge's bearing moved by this many degrees would: a gain that shrinks as the network
// grows (a fixed one, 1e-4, stopped every move over six times the counties' side: 15 000 edges).
constexpr double kShiftGainDegrees = 1.0;

// The other properties' distances to the exemplar's may grow by this part of the exemplar's own
// half-to-half distance (its variability) over the pass, no more; a round that goes beyond is
// undone.
constexpr double kShiftAllowance = 0.1;

// Bearings counted in bins of 0.1° (as the twigs' pass counts them).
constexpr int kShiftBearingBins = 1800;

// A polyline from `at` (its first point) deformed so that that end moves by `by` and its other
// end stays: each vertex moved by `by` times its share of the length still to go.
std::vector<Vec2> shifted_from_start(const std::vector<Vec2>& pts, Vec2 by) {
  const double length = polyline_length(pts);
  std::vector<Vec2> out = pts;
  double walked = 0.0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    if (k > 0) walked += distance(pts[k - 1], pts[k]);
    out[k] = pts[k] + by * (length > 0.0 ? 1.0 - walked / length : 0.0);
  }
  out.back() = pts.back();
  return out;
}

// The distances, property by property but the bearings, of a network's statistics to the
// exemplar's (degree, edge length, curvature, junction angle, face area).
std::array<double, 5> other_distances(const NetworkStats& exemplar, const NetworkStats& output) {
  std::array<double, 5> d{};
  for (int p = 0; p < 5; ++p)
    d[std::size_t(p)] = normalized_w1(property(exemplar, p), property(output, p));
  return d;
}

}  // namespace

// Where the exemplar's cells are closed and whole (keep_whole_cells) and its edges bend, or its
// lines end free (a forest), a junction's exact place is within the wobble of the lines meeting
// there, but every edge's chord bearing hangs on it: the quilt's blocks and growth's pieces bring
// the exemplar's bearings in the proportions the blocks or pieces drawn happen to have (the
// county map's 300 edges, a few degrees off bin by bin: as far from the exemplar as a placement
// of random squares), and a forest's twigs pruned for bearings (prune_twigs_for_bearings, run
// first) leave what no whole twig fixes. So junctions are moved by a few hundredths of a median
// edge, each of its lines deformed along its length (its far end staying), where that brings
// the output's chord bearings nearest the exemplar's, the best first, while the distance falls,
// each line committed under the rules of every line ("Guarantees") and the other properties kept
// within a tenth of the exemplar's own half-to-half distances of where they were. Not where the
// cells are straight: their lines go straight through their junctions (Ts), which a shift would
// bend.
void Grower::shift_junctions_for_bearings() {
  const bool closed_bent_cells = whole_cells_ && straight_share_ < kStraightShare;
  if (!(forest_ || closed_bent_cells) || completing_ || exemplar_bearings_.size() < 2) return;
  const BinnedW1 bearing_w1(exemplar_bearings_, 180.0 / kShiftBearingBins, kShiftBearingBins);
  const NetworkStats exemplar_stats = network_stats(exemplar_);
  std::array<double, 5> allowed{};
  {
    const auto [one, other] = halves(exemplar_);
    const std::array<double, 5> own =
        other_distances(network_stats(exemplar_, one), network_stats(exemplar_, other));
    const std::array<double, 5> now = other_distances(exemplar_stats, network_stats(finish()));
    for (std::size_t p = 0; p < allowed.size(); ++p)
      allowed[p] = now[p] + kShiftAllowance * own[p] + 1e-12;
  }
  struct Made {
    std::vector<int> old_edges, new_edges, emptied;
    int new_node = -1;
  };
  // A move undone: its new lines gone, the old ones back.
  const auto undo = [&](const Made& done) {
    for (int e : done.new_edges) {
      index_edge(e, false);
      alive_[std::size_t(e)] = 0;
      --degree_[std::size_t(out_.edges[std::size_t(e)].from)];
      --degree_[std::size_t(out_.edges[std::size_t(e)].to)];
    }
    if (done.new_node >= 0)
      nodes_.remove(NodeValue{to_bg(out_.nodes[std::size_t(done.new_node)]), done.new_node});
    for (int n : done.emptied) nodes_.insert({to_bg(out_.nodes[std::size_t(n)]), n});
    for (int e : done.old_edges) {
      alive_[std::size_t(e)] = 1;
      ++degree_[std::size_t(out_.edges[std::size_t(e)].from)];
      ++degree_[std::size_t(out_.edges[std::size_t(e)].to)];
      index_edge(e, true);
    }
  };
  // Every move made, in order, and where each round's moves begin.
  std::vector<Made> made;
  std::vector<std::size_t> round_starts;
  std::size_t budget = 0;
  double first_gain = 0.0;
  for (int round = 0; round < kShiftRounds; ++round) {
    round_starts.push_back(made.size());
    const std::vector<Chain> all = chains();
    std::vector<std::vector<int>> at(out_.nodes.size());
    std::vector<double> bearings(kShiftBearingBins, 0.0);
    double total = 0.0;
    const auto bin_of = [&](Vec2 chord) {
      return chord == Vec2{} ? -1 : bearing_w1.bin(chord_bearing(chord));
    };
    std::vector<int> bin(all.size(), -1);
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Chain& c = all[i];
      at[std::size_t(c.from)].push_back(int(i));
      if (c.to != c.from) at[std::size_t(c.to)].push_back(int(i));
      bin[i] = bin_of(c.points.back() - c.points.front());
      if (bin[i] >= 0) bearings[std::size_t(bin[i])] += 1.0, total += 1.0;
    }
    if (round == 0) {
      std::size_t junctions = 0;
      for (const auto& a : at) junctions += a.size() >= 3;
      budget = std::size_t(kShiftShare * double(junctions));
    }
    // A node's move: its chains' bins replaced by those of their chords from the moved node.
    struct Move {
      int node = -1;
      Vec2 by;
      double after = 0.0;
    };
    const auto movable = [&](int n) {
      if (at[std::size_t(n)].size() < 3 || out_.on_boundary[std::size_t(n)]) return false;
      for (int c : at[std::size_t(n)]) {
        const Chain& chain = all[std::size_t(c)];
        if (chain.kept || chain.from == chain.to || bin[std::size_t(c)] < 0) return false;
      }
      return true;
    };
    const auto apply = [&](int n, Vec2 by, double sign) {
      const Vec2 p = out_.nodes[std::size_t(n)];
      for (int c : at[std::size_t(n)]) {
        const Chain& chain = all[std::size_t(c)];
        const Vec2 far = chain.from == n ? chain.points.back() : chain.points.front();
        bearings[std::size_t(bin[std::size_t(c)])] -= sign;
        const int moved = bin_of(far - (p + by));
        if (moved >= 0)
          bearings[std::size_t(moved)] += sign;
        else
          total -= sign;
      }
    };
    std::vector<Move> moves;
    const double now_before = bearing_w1.apart(bearings, total);
    const double least_gain = bearing_w1.one_count_moved(kShiftGainDegrees, total);
    std::vector<double> running(bearings.size());
    for (std::size_t k = 0; k < bearings.size(); ++k)
      running[k] = bearings[k] + (k > 0 ? running[k - 1] : 0.0);
    std::vector<std::pair<int, int>> rebinned;
    for (std::size_t n = 0; n < at.size(); ++n) {
      if (!movable(int(n))) continue;
      Move best{int(n), {}, now_before};
      for (double step : kShiftSteps)
        for (int d = 0; d < kShiftDirections; ++d) {
          const double h = 2.0 * kPi * d / kShiftDirections;
          const Vec2 by = step * median_ * Vec2{std::cos(h), std::sin(h)};
          rebinned.clear();
          for (int c : at[n]) {
            const Chain& chain = all[std::size_t(c)];
            const Vec2 far = chain.from == int(n) ? chain.points.back() : chain.points.front();
            rebinned.push_back({bin[std::size_t(c)], bin_of(far - (out_.nodes[n] + by))});
          }
          if (std::any_of(rebinned.begin(), rebinned.end(), [](auto m) { return m.second < 0; }))
            continue;
          const double after = now_before + bearing_w1.apart_change(running, total, rebinned);
          if (after < best.after) best.after = after, best.by = by;
        }
      if (best.after < now_before - least_gain) moves.push_back(best);
    }
    std::stable_sort(moves.begin(), moves.end(),
                     [](const Move& a, const Move& b) { return a.after < b.after; });
    // This round's moves, best first, each on the counts with those before it made: none
    // sharing a chain with another.
    double now = now_before;
    std::vector<char> node_used(out_.nodes.size(), 0);
    for (const Move& m : moves) {
      if (budget == 0) break;
      if (node_used[std::size_t(m.node)]) continue;
      apply(m.node, m.by, 1.0);
      const double after = bearing_w1.apart(bearings, total);
      if (!(after < now - least_gain)) {
        apply(m.node, m.by, -1.0);
        continue;
      }
      // The lines from the moved node, committed one by one under the rules of every line.
      Made done;
      for (int c : at[std::size_t(m.node)])
        for (int e : all[std::size_t(c)].edges) done.old_edges.push_back(e), index_edge(e, false);
      for (int e : done.old_edges) {
        alive_[std::size_t(e)] = 0;
        --degree_[std::size_t(out_.edges[std::size_t(e)].from)];
        --degree_[std::size_t(out_.edges[std::size_t(e)].to)];
      }
      // The node and the nodes its lines passed, left without edges, are no seeds to keep
      // clear of (valid keeps new lines off such nodes).
      for (int e : done.old_edges)
        for (int n : {out_.edges[std::size_t(e)].from, out_.edges[std::size_t(e)].to})
          if (degree_[std::size_t(n)] == 0 &&
              std::find(done.emptied.begin(), done.emptied.end(), n) == done.emptied.end()) {
            done.emptied.push_back(n);
            nodes_.remove(NodeValue{to_bg(out_.nodes[std::size_t(n)]), n});
          }
      const Vec2 to = out_.nodes[std::size_t(m.node)] + m.by;
      bool ok = inside_region(to) && !forbidden_at(to, true) && clear_of_lines(to);
      if (ok) done.new_node = add_node(to);
      for (std::size_t k = 0; ok && k < at[std::size_t(m.node)].size(); ++k) {
        const Chain& chain = all[std::size_t(at[std::size_t(m.node)][k])];
        std::vector<Vec2> pts = chain.points;
        if (chain.to == m.node) std::reverse(pts.begin(), pts.end());
        pts = shifted_from_start(pts, m.by);
        if (!valid(pts, true, Spacing::copied)) {
          ok = false;
          break;
        }
        NetworkEdge e = out_.edges[std::size_t(chain.edges.front())];
        e.from = done.new_node;
        e.to = chain.from == m.node ? chain.to : chain.from;
        e.points = std::move(pts);
        done.new_edges.push_back(add_edge(std::move(e)));
      }
      if (!ok) {
        undo(done);
        apply(m.node, m.by, -1.0);
        continue;
      }
      now = after;
      node_used[std::size_t(m.node)] = 1;
      for (int c : at[std::size_t(m.node)]) {
        const Chain& chain = all[std::size_t(c)];
        node_used[std::size_t(chain.from)] = node_used[std::size_t(chain.to)] = 1;
      }
      made.push_back(std::move(done));
      --budget;
    }
    if (made.size() == round_starts.back()) {
      round_starts.pop_back();
      break;
    }
    if (round == 0) first_gain = now_before - now;
    if (now_before - now < kShiftLastGain * first_gain) break;
  }
  // The moves are kept while the other properties stay within their allowance: else the later
  // half of the last round's moves is undone (the smaller gains), and again, until they are.
  while (!made.empty()) {
    const std::array<double, 5> d = other_distances(exemplar_stats, network_stats(finish()));
    bool within = true;
    for (std::size_t p = 0; p < d.size(); ++p) within = within && d[p] <= allowed[p];
    if (within) break;
    const std::size_t start = round_starts.back();
    for (std::size_t keep = start + (made.size() - start) / 2; made.size() > keep; made.pop_back())
      undo(made.back());
    if (made.size() == start) round_starts.pop_back();
  }
}

}  // namespace tw::network_detail
