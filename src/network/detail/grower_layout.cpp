// Grower: the layout of the exemplar's long strokes (docs/networks.md, "Layout").

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "network/detail/border.hpp"
#include "network/detail/forest.hpp"
#include "network/detail/grower.hpp"
#include "network/detail/quilt.hpp"
#include "network/detail/skeleton.hpp"
#include "network/stats.hpp"

namespace tw::network_detail {

// The exemplar's long strokes (the tracks of a grid, terrace walls, rings and spokes) copied
// rigidly as one piece, repeated at the exemplar's extent to cover the region (a seeded shift
// of at most half a median edge), committed under the same rules as quilted lines; each of
// their junctions then gets stubs along the exemplar's other edges there, from which growth
// fills the cells. A copied dangling end too near a line is moved to keep the clearance, and
// the copies' empty parts get no lattice seed (layout_copies.hpp). False when the exemplar has
// no such strokes.
bool Grower::lay_out_long_strokes() {
  const std::vector<double> skeleton =
      long_stroke_edges(exemplar_, kStrokeDeflection, kLayoutStrokeFraction, kLayoutShare);
  // The longest strokes first (rings, whole tracks): a shorter one ending short of them, as
  // drawn exemplars' lines do, gives way.
  std::vector<std::size_t> order;
  for (std::size_t e = 0; e < skeleton.size(); ++e)
    if (skeleton[e] > 0.0) order.push_back(e);
  if (order.empty()) return false;
  // An edge ending in a dangling end of the exemplar comes after those that do not: a drawn
  // line ending a hair short of another (a near T) then has its end moved back to keep the
  // clearance, instead of blocking the line it almost meets.
  const std::vector<int> exemplar_degree = exemplar_.degrees();
  const auto dangles = [&](std::size_t e) {
    return exemplar_degree[std::size_t(exemplar_.edges[e].from)] == 1 ||
           exemplar_degree[std::size_t(exemplar_.edges[e].to)] == 1;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (dangles(a) != dangles(b)) return dangles(b);
    return skeleton[a] > skeleton[b];
  });
  const NodeExtent extent = node_extent(exemplar_);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const Vec2 centre = 0.5 * (lo + hi), size = hi - lo;
  if (!(size.x > 0.0 && size.y > 0.0)) return false;
  const Vec2 region_lo = vec(extent_.min_corner()), region_hi = vec(extent_.max_corner());
  const Vec2 shift{rng_.uniform(-0.5, 0.5) * median_, rng_.uniform(-0.5, 0.5) * median_};
  const Vec2 origin = 0.5 * (region_lo + region_hi) + shift;
  const double reach = 0.5 * distance(region_lo, region_hi) + median_;
  const int ni = int(std::ceil(reach / size.x)), nj = int(std::ceil(reach / size.y));
  std::vector<std::pair<int, int>> tiles;
  for (int j = -nj; j <= nj; ++j)
    for (int i = -ni; i <= ni; ++i) tiles.push_back({i, j});
  // The middle first: its copy is whole, the others fill around it.
  std::stable_sort(tiles.begin(), tiles.end(), [](auto a, auto b) {
    return a.first * a.first + a.second * a.second < b.first * b.first + b.second * b.second;
  });
  const std::vector<int> degree = exemplar_.degrees();
  // Per exemplar node, the headings of its edges that are not laid out: the stubs growth
  // fills the cells from.
  std::vector<std::vector<std::pair<double, int>>> grown_headings(exemplar_.nodes.size());
  for (std::size_t e = 0; e < exemplar_.edges.size(); ++e) {
    if (skeleton[e] > 0.0) continue;
    const NetworkEdge& edge = exemplar_.edges[e];
    grown_headings[std::size_t(edge.from)].push_back(
        {leaving(edge.points, true) + turn_, piece_of_[2 * e]});
    grown_headings[std::size_t(edge.to)].push_back(
        {leaving(edge.points, false) + turn_, piece_of_[2 * e + 1]});
  }
  std::vector<char> laid(out_.nodes.size(), 0);
  // Copies whose corners are empty are islands: turned (by a lead bearing), each turns about
  // its own centre on the region's grid, or a neighbour's ring would reach into the region's
  // corners.
  LayoutFrame frame{origin, centre, size, lo, hi, turn_, ni, nj};
  layout_copies_.emplace(exemplar_, frame);
  // (Unturned, both grids are one: the copies stay as they were, to the bit.)
  frame.islands = turn_ != 0.0 && layout_copies_->corners_empty(kLayoutEmptyReach * median_);
  layout_copies_.emplace(exemplar_, frame);
  for (auto [i, j] : tiles) {
    const auto place = [&](Vec2 p) { return frame.place(p, i, j); };
    std::vector<std::pair<int, int>> copied;  // (exemplar node, output node)
    for (std::size_t e : order) {
      const NetworkEdge& edge = exemplar_.edges[e];
      std::vector<Vec2> pts;
      for (Vec2 p : edge.points) pts.push_back(place(p));
      for (std::vector<Vec2>& part : inside_parts(std::move(pts))) {
        // A line grazing the region's edge (a corner of the exemplar's own edge, where a
        // ramp turns into a wall, shifted just inside) leaves a part cut at both ends, shorter
        // than a typical edge, turning sharply: not copied.
        if (polyline_length(part) < median_ && near_boundary(part.front()) &&
            near_boundary(part.back()))
          continue;
        std::vector<Vec2> kept = part;
        if (!place_line(std::move(part), clearance_, Spacing::laid_out)) {
          // An exemplar's dangling end (degree 1) the copy kept uncut.
          const auto free_end = [&](int end, Vec2 p) {
            return degree[std::size_t(end)] == 1 && p == place(exemplar_.nodes[std::size_t(end)]);
          };
          kept = with_free_ends_clear(std::move(kept), free_end(edge.from, kept.front()),
                                      free_end(edge.to, kept.back()), clearance_,
                                      [&](Vec2 p) { return clear_of_lines(p); });
          if (kept.empty() || !place_line(kept, clearance_, Spacing::laid_out)) continue;
        }
        count_line(kept);
        for (int end : {edge.from, edge.to}) {
          const Vec2 p = place(exemplar_.nodes[std::size_t(end)]);
          const auto it = node_at_.find({p.x, p.y});
          if (it != node_at_.end()) copied.push_back({end, it->second});
        }
      }
    }
    laid.resize(out_.nodes.size(), 0);
    for (auto [from, node] : copied) {
      if (laid[std::size_t(node)] || out_.on_boundary[std::size_t(node)]) continue;
      laid[std::size_t(node)] = 1;
      planned_[std::size_t(node)] = degree[std::size_t(from)];
      have_degree_[std::size_t(std::min(degree[std::size_t(from)], 6))] += 1.0;
      junction_count_ += 1.0;
      for (auto [h, piece] : grown_headings[std::size_t(from)]) push_stub(node, h, piece);
    }
  }
  return true;
}

}  // namespace tw::network_detail
