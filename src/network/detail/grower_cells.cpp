// Grower: cells larger than the exemplar's split by straight chords (docs/networks.md, "Growth",
// step 10).

#include <ogr_geometry.h>

#include <algorithm>
#include <cmath>
#include <memory>
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

// Where the exemplar's cells are closed, its edges straight and its lines end on each other in
// Ts (fields split by straight hedges; max_cell_area_ is 0 elsewhere), a cell of the output larger
// than the exemplar's largest is one no line split: it is split by a straight chord from the middle
// of its longest side, square to it, onto the line across (a T at each end, as the exemplar's
// chords make), under the rules of every line; else from the middle of the next longest side; else
// from a third of the way along a side. Until no cell is larger, or no chord is valid.
void Grower::split_large_cells() {
  if (!(max_cell_area_ > 0.0) || completing_) return;
  const double eps = 1e-7 * median_;
  for (int round = 0; round < kSplitRounds; ++round) {
    OGRMultiLineString all;
    for (std::size_t i = 0; i < out_.edges.size(); ++i) {
      if (!alive_[i]) continue;
      OGRLineString ls;
      for (Vec2 p : out_.edges[i].points) ls.addPoint(p.x, p.y);
      all.addGeometry(&ls);
    }
    const std::unique_ptr<OGRGeometry> faces(all.Polygonize());
    if (!faces) return;
    std::vector<std::vector<Vec2>> large;
    for (const OGRGeometry* g : *faces->toGeometryCollection()) {
      if (wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
      const OGRPolygon* cell = g->toPolygon();
      if (cell->get_Area() <= max_cell_area_) continue;
      std::vector<Vec2> ring;
      for (const OGRPoint& p : *cell->getExteriorRing()) ring.push_back({p.getX(), p.getY()});
      if (ring.size() >= 4) large.push_back(std::move(ring));
    }
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
      const std::vector<CellSide> sides = cell_sides(ring);
      for (double share : kChordPlaces) {
        for (const CellSide& side : sides)
          if (chord_from(side, share)) {
            split = true;
            break;
          }
        if (split) break;
      }
    }
    if (!split) return;
  }
}

}  // namespace tw::network_detail
