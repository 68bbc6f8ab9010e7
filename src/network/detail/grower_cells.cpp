// Grower: cells larger than the exemplar's split by straight chords, cells smaller than its
// smallest merged into a neighbour (docs/networks.md, "Growth", steps 9 and 10).

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/segment_distance.hpp"
#include "network/detail/grower.hpp"

namespace tw::network_detail {

namespace {

// Consecutive segments of a cell's ring turning less than this (radians) are one side.
constexpr double kSideTurn = 0.05;

// How many times the cells are taken again (a split cell's halves may still be too large).
constexpr int kSplitRounds = 4;

// Where along a side a chord starts, in the order tried (the exemplar's chords start within
// its sides' middle third or so).
constexpr double kChordPlaces[] = {0.5, 0.35, 0.65};

// How many times the small cells are taken again (a merged pair may still be too small).
constexpr int kMergeRounds = 4;

// Whether p lies on one of the cell's rings (within eps).
bool on_cell_rings(const CellCycles::Cell& cell, Vec2 p, double eps) {
  if (p.x < cell.lo.x - eps || p.y < cell.lo.y - eps || p.x > cell.hi.x + eps ||
      p.y > cell.hi.y + eps)
    return false;
  for (const std::vector<Vec2>& ring : cell.rings)
    for (std::size_t k = 0; k + 1 < ring.size(); ++k)
      if (distance_to_segment(p, ring[k], ring[k + 1]) <= eps) return true;
  return false;
}

// The middle of a line's longest step: a point on it away from its nodes.
Vec2 middle_of_longest_step(const std::vector<Vec2>& pts) {
  std::size_t best = 0;
  for (std::size_t k = 1; k + 1 < pts.size(); ++k)
    if (distance(pts[k], pts[k + 1]) > distance(pts[best], pts[best + 1])) best = k;
  return lerp(pts[best], pts[best + 1], 0.5);
}

// A cell's side: from ring vertex `first` to ring vertex `last` (indices into the ring, which
// closes on itself), and its length.
struct CellSide {
  std::size_t first = 0, last = 0;
  double length = 0.0;
};

// The sides of a closed ring (its last point repeats its first), longest first.
std::vector<CellSide> cell_sides(const std::vector<Vec2>& ring) {
  const std::size_t n = ring.size() - 1;
  // Start at a vertex where the ring turns, so that no side wraps round the first point.
  const auto turns_at = [&](std::size_t k) {
    const Vec2 a = ring[(k + n - 1) % n], b = ring[k], c = ring[(k + 1) % n];
    return polyline_turning({a, b, c}) >= kSideTurn;
  };
  std::size_t start = 0;
  while (start < n && !turns_at(start)) ++start;
  if (start == n) return {};
  std::vector<CellSide> sides;
  CellSide side{start, start, 0.0};
  for (std::size_t step = 1; step <= n; ++step) {
    const std::size_t k = (start + step) % n;
    side.length += distance(ring[(k + n - 1) % n], ring[k]);
    side.last = k;
    if (turns_at(k)) {
      sides.push_back(side);
      side = {k, k, 0.0};
    }
  }
  std::sort(sides.begin(), sides.end(),
            [](const CellSide& a, const CellSide& b) { return a.length > b.length; });
  return sides;
}

// The point `share` of the way along a side, and the ring segment it lies on.
std::pair<Vec2, std::size_t> side_point(const std::vector<Vec2>& ring, const CellSide& side,
                                        double share) {
  const std::size_t n = ring.size() - 1;
  double left = share * side.length;
  for (std::size_t k = side.first; k != side.last; k = (k + 1) % n) {
    const Vec2 a = ring[k], b = ring[(k + 1) % n];
    const double l = distance(a, b);
    if (left <= l) return {lerp(a, b, l > 0.0 ? left / l : 0.0), k};
    left -= l;
  }
  return {ring[side.last], side.last};
}

}  // namespace

// Where the exemplar's cells are closed, its edges straight (max_cell_area_ is 0 elsewhere) and
// its lines end on each other in Ts (cells_end_in_ts_: fields split by straight hedges, not the
// crocodile's Ys), a cell of the output larger
// than the exemplar's largest is one no line split: it is split by a straight chord from the middle
// of its longest side, square to it, onto the line across (a T at each end, as the exemplar's
// chords make), under the rules of every line; else from the middle of the next longest side; else
// from a third of the way along a side. Until no cell is larger, or no chord is valid.
void Grower::split_large_cells(CellCycles& cells) {
  if (!(max_cell_area_ > 0.0) || !cells_end_in_ts_ || completing_) return;
  const double eps = 1e-7 * median_;
  for (int round = 0; round < kSplitRounds; ++round) {
    std::vector<std::vector<Vec2>> large;
    for (const CellCycles::Cell* cell : cells.cells())
      if (cell->area > max_cell_area_) large.push_back(cell->rings[0]);
    bool split = false;
    for (const std::vector<Vec2>& ring : large) {
      double twice_area = 0.0;  // > 0: counter-clockwise, the inside on the left
      for (std::size_t k = 0; k + 1 < ring.size(); ++k) twice_area += cross(ring[k], ring[k + 1]);
      Vec2 lo = ring[0], hi = ring[0];
      for (Vec2 p : ring)
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      const double reach = distance(lo, hi);
      // A chord square to the side from the point `share` of the way along it.
      const auto chord_from = [&](const CellSide& side, double share) {
        const auto [start, k] = side_point(ring, side, share);
        const double inward =
            heading(ring[k + 1] - ring[k]) + (twice_area > 0.0 ? 0.5 : -0.5) * kPi;
        // The output edge the point lies on, away from its ends.
        std::vector<SegValue> near;
        segments_.query(bgi::nearest(to_bg(start), 1), std::back_inserter(near));
        if (near.empty() || bg::distance(near[0].first, to_bg(start)) > eps) return false;
        const int id = near[0].second;
        const NetworkEdge& e = out_.edges[std::size_t(id)];
        if (distance(start, out_.nodes[std::size_t(e.from)]) < clearance_ ||
            distance(start, out_.nodes[std::size_t(e.to)]) < clearance_)
          return false;
        std::size_t seg = 0;
        double best = INFINITY;
        for (std::size_t s = 0; s + 1 < e.points.size(); ++s)
          if (const double d = distance_to_segment(start, e.points[s], e.points[s + 1]); d < best)
            best = d, seg = s;
        // Tried before a node is made: the ray must meet another line.
        const std::vector<Vec2> ray{start,
                                    start + Vec2{std::cos(inward), std::sin(inward)} * reach};
        const auto hit = first_edge_hit(ray);
        if (!hit || hit->edge == id) return false;
        // An invalid chord leaves the new node of degree 2 on a straight side, merged away as
        // the network is written (finish).
        return link_ahead(split_edge(id, int(seg), start), inward, reach, id);
      };
      // Every place along every side is tried for this cell until one chord is valid (a cell
      // split before it in the round does not cut its tries short).
      bool this_split = false;
      const std::vector<CellSide> sides = cell_sides(ring);
      for (double share : kChordPlaces) {
        for (const CellSide& side : sides)
          if (chord_from(side, share)) {
            this_split = true;
            break;
          }
        if (this_split) break;
      }
      split = split || this_split;
    }
    if (!split) return;
  }
}

// Where the exemplar's cells are closed and its edges straight, a cell of the output smaller
// than the exemplar's smallest is a sliver between two lines that a field apart would not have:
// it is merged into a neighbour by taking off the line between them, junction to junction,
// where that leaves no dead end and no bent corner at either end (ends_left_at: each end stays
// a junction or a line going straight through it) and the merged cell is no larger than the
// exemplar's largest; the neighbour making the smaller merged cell first. Smallest cells first,
// until none is left small or none can be merged. Whether any was (the lines that went straight
// through a freed junction within a stroke's deflection are then straightened: straighten_kinks).
bool Grower::merge_small_cells(CellCycles& found) {
  if (!(min_cell_area_ > 0.0) || completing_) return false;
  const double eps = 1e-6 * median_;
  bool merged_any = false;
  for (int round = 0; round < kMergeRounds; ++round) {
    const std::vector<const CellCycles::Cell*> cells = found.cells();
    // The cells by their boxes: a line's probe meets a few, not all (the pass stays near
    // linear in the network's size).
    std::vector<std::pair<BgBox, std::size_t>> boxes;
    for (std::size_t f = 0; f < cells.size(); ++f)
      boxes.emplace_back(BgBox(to_bg(cells[f]->lo), to_bg(cells[f]->hi)), f);
    const bgi::rtree<std::pair<BgBox, std::size_t>, bgi::rstar<16>> cell_index(boxes);
    std::vector<Chain> lines = chains();
    // Per line taken off: the two cells it parts (none when it parts fewer or more).
    struct Parting {
      std::size_t line = 0, small = 0, other = 0;
      double merged = 0.0;
    };
    std::vector<Parting> partings;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const Chain& c = lines[i];
      if (c.kept || c.from == c.to) continue;
      const Vec2 probe = middle_of_longest_step(c.points);
      std::vector<std::size_t> near;  // in the cells' order, as a scan of them all would be
      for (auto it = cell_index.qbegin(bgi::intersects(
               BgBox(to_bg(probe - Vec2{eps, eps}), to_bg(probe + Vec2{eps, eps}))));
           it != cell_index.qend(); ++it)
        near.push_back(it->second);
      std::sort(near.begin(), near.end());
      std::vector<std::size_t> sides;
      for (std::size_t k = 0; k < near.size() && sides.size() < 3; ++k)
        if (on_cell_rings(*cells[near[k]], probe, eps)) sides.push_back(near[k]);
      if (sides.size() != 2) continue;
      const double merged = cells[sides[0]]->area + cells[sides[1]]->area;
      if (merged > max_cell_area_) continue;
      for (int k = 0; k < 2; ++k)
        if (cells[sides[std::size_t(k)]]->area < min_cell_area_)
          partings.push_back({i, sides[std::size_t(k)], sides[std::size_t(1 - k)], merged});
    }
    std::sort(partings.begin(), partings.end(), [&](const Parting& a, const Parting& b) {
      return std::pair(cells[a.small]->area, a.merged) < std::pair(cells[b.small]->area, b.merged);
    });
    std::vector<char> taken(cells.size(), 0);
    bool merged = false;
    for (const Parting& p : partings) {
      if (taken[p.small] || taken[p.other]) continue;
      const Chain& c = lines[p.line];
      if (ends_left_at(c.from, c) != 0 || ends_left_at(c.to, c) != 0) continue;
      take_off(c);
      taken[p.small] = taken[p.other] = 1;
      merged = true;
    }
    if (!merged) break;
    merged_any = true;
  }
  return merged_any;
}

}  // namespace tw::network_detail
