// Grower: quilting (docs/networks.md, "Quilting"); links onto the network, trimming, whole cells.

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

namespace {

// How far (median edge lengths) a corner's edge is continued to make it a T-junction (3 and 6
// met fewer targets over three seeds: long links break cells).
constexpr double kCornerReach = 1.5;

// A quilt's seam end left alone is linked onto a line within this many median edge lengths.
constexpr double kSeamReach = 1.5;

}  // namespace

// The quilt's lines are committed one by one under the same rules as grown pieces (no
// crossing but at shared nodes, clearance, region, forbidden cells): a line that breaks one
// is left out. Seam ends that found no partner are linked straight onto the line ahead, or
// trimmed back to the last junction.
void Grower::quilt() {
  QuiltSettings settings;
  settings.lo = vec(extent_.min_corner());
  settings.hi = vec(extent_.max_corner());
  settings.stitch = 0.6 * snap_;
  settings.clearance = clearance_;
  settings.turn = turn_;
  settings.candidates = 32;
  settings.continuation = kSeamReach * median_;
  std::vector<QuiltLine> lines = quilt_lines(exemplar_, settings, rng_);
  std::vector<std::pair<Vec2, std::vector<Vec2>>> seam_ends;  // and their continuations
  for (QuiltLine& line : lines) {
    for (int end = 0; end < 2; ++end)
      if (line.seam_end[end])
        seam_ends.push_back({end == 0 ? line.points.front() : line.points.back(),
                             std::move(line.continuation[end])});
    for (std::vector<Vec2>& part : inside_parts(line.points)) {
      // A dip into the region shorter than a piece (both ends on its boundary) is left out:
      // an edge the exemplar, which no boundary cuts, does not have.
      if (near_boundary(part.front()) && near_boundary(part.back()) &&
          polyline_length(part) < min_piece_)
        continue;
      place_line(std::move(part));
    }
  }
  for (auto& [p, continuation] : seam_ends) {
    const auto it = node_at_.find({p.x, p.y});
    if (it == node_at_.end()) continue;
    const int n = it->second;
    if (degree_[std::size_t(n)] != 1 || out_.on_boundary[std::size_t(n)]) continue;
    int edge = -1;
    for (int i : incident_[std::size_t(n)])
      if (alive_[std::size_t(i)]) edge = i;
    const NetworkEdge& e = out_.edges[std::size_t(edge)];
    // Along the exemplar's own line beyond the cut first (its bends and bearing), else
    // straight ahead.
    if (continuation.size() >= 2 && link_along(n, continuation, edge)) continue;
    if (link_ahead(n, leaving(e.points, e.from == n) + kPi, kSeamReach * median_, edge)) continue;
    trim_from(n, median_);
  }
  close_corners();  // a junction that lost a line to the trimming or the rules
}

// A dangling end removed with its edge, and the chain behind it up to the last junction (at
// most `at_most` metres of line); the node where it stopped.
int Grower::trim_from(int n, double at_most) {
  double trimmed = 0.0;
  while (degree_[std::size_t(n)] == 1 && !out_.on_boundary[std::size_t(n)] && trimmed < at_most) {
    int edge = -1;
    for (int i : incident_[std::size_t(n)])
      if (alive_[std::size_t(i)]) edge = i;
    if (edge < 0 || out_.edges[std::size_t(edge)].kept) return n;
    const NetworkEdge& e = out_.edges[std::size_t(edge)];
    const int other = e.from == n ? e.to : e.from;
    trimmed += polyline_length(e.points);
    index_edge(edge, false);
    alive_[std::size_t(edge)] = 0;
    --degree_[std::size_t(n)];
    --degree_[std::size_t(other)];
    ++report_.pruned;
    n = other;
  }
  return n;
}

// A straight link from node n along `heading` onto the first line ahead within `reach`, when
// valid: the node becomes a junction.
bool Grower::link_ahead(int n, double heading, double reach, int own_edge) {
  return link_along(n, ray_from(n, heading, reach), own_edge);
}

// Node n joined along `ray` (a polyline from it) onto the first line it meets, when that is
// valid.
bool Grower::link_along(int n, std::vector<Vec2> ray, int own_edge) {
  // The link starts at the node, as it is committed (a quilt seam end's continuation starts
  // where the end was cut, before stitching moved it).
  ray.front() = out_.nodes[std::size_t(n)];
  const auto hit = first_edge_hit(ray);
  if (!hit || hit->edge == own_edge) return false;
  truncate(ray, *hit);
  const NetworkEdge& e = out_.edges[std::size_t(hit->edge)];
  if (polyline_length(ray) < min_piece_ ||
      distance(ray.back(), out_.nodes[std::size_t(e.from)]) < clearance_ ||
      distance(ray.back(), out_.nodes[std::size_t(e.to)]) < clearance_ ||
      meeting_angle(ray, e.points[std::size_t(hit->seg)], e.points[std::size_t(hit->seg) + 1]) <
          kMinMeetingAngle ||
      !valid(ray, true))
    return false;
  link_onto(n, std::move(ray), *hit);
  return true;
}

// Node n joined by `ray` (truncated at `hit`) onto the line it hits: that line is split there
// and the link ends on the new junction.
void Grower::link_onto(int n, std::vector<Vec2> ray, const Hit& hit) {
  const int t = split_edge(hit.edge, hit.seg, ray.back());
  link_to(n, std::move(ray), t);
}

// Node n joined by `ray` to node `to` (its last point moved onto it): a new edge.
void Grower::link_to(int n, std::vector<Vec2> ray, int to) {
  ray.back() = out_.nodes[std::size_t(to)];
  NetworkEdge link;
  link.from = n;
  link.to = to;
  link.points = std::move(ray);
  add_edge(std::move(link));
  if (cell_cycles_) cell_cycles_->chord_added(int(out_.edges.size()) - 1);
}

// Nodes left with two edges at a corner (a junction whose other stubs found nothing) would be
// merged into a bent edge the exemplar does not have: one of the edges is continued straight
// through the node onto the line ahead, making the corner a T-junction, when that is valid.
void Grower::close_corners() {
  const std::size_t nodes = out_.nodes.size();
  for (std::size_t n = 0; n < nodes; ++n) {
    if (degree_[n] != 2 || out_.on_boundary[n]) continue;
    std::vector<int> edges;
    for (int e : incident_[n])
      if (alive_[std::size_t(e)]) edges.push_back(e);
    if (edges.size() != 2 || out_.edges[std::size_t(edges[0])].kept ||
        out_.edges[std::size_t(edges[1])].kept)
      continue;
    double h[2];
    for (int k = 0; k < 2; ++k) {
      const NetworkEdge& e = out_.edges[std::size_t(edges[std::size_t(k)])];
      h[k] = leaving(e.points, e.from == int(n));
    }
    if (std::abs(wrap(h[0] - h[1] - kPi)) < kCornerTurn) continue;  // nearly straight
    bool closed = false;
    for (int k = 0; k < 2 && !closed; ++k)
      closed = link_ahead(int(n), h[k] + kPi, kCornerReach * median_, edges[std::size_t(1 - k)]);
    // Else straight on to the region's boundary when nothing lies between (the corner becomes a
    // T whose third edge leaves the region, as lines cut by the region do).
    for (int k = 0; k < 2 && !closed; ++k)
      closed = link_to_boundary(int(n), h[k] + kPi, kCornerReach * median_);
  }
}

// A straight link from node n along `heading` to the region's boundary within `reach`, when
// no line lies between and it is valid: the node becomes a junction.
bool Grower::link_to_boundary(int n, double heading, double reach) {
  std::vector<Vec2> ray = ray_from(n, heading, reach);
  const auto wall = first_boundary_hit(ray);
  if (!wall) return false;
  truncate(ray, *wall);
  if (first_edge_hit(ray) || polyline_length(ray) < min_piece_) return false;
  ray.back() = ray.back() +
               (ray.front() - ray.back()) * std::min(0.5, 1e-9 * median_ / polyline_length(ray));
  if (!valid(ray, false)) return false;
  const int end = add_node(ray.back());
  out_.on_boundary[std::size_t(end)] = 1;
  link_to(n, std::move(ray), end);
  return true;
}

// Dangling ends beyond the exemplar's rate: joined onto the network straight ahead when a
// short, valid link exists, else short dead ends are pruned.
void Grower::close_dangling_ends() {
  double length = 0.0;
  for (std::size_t i = 0; i < out_.edges.size(); ++i)
    length += polyline_length(out_.edges[i].points);
  std::vector<int> ends;
  for (std::size_t n = 0; n < out_.nodes.size(); ++n)
    if (degree_[n] == 1 && !out_.on_boundary[n]) ends.push_back(int(n));
  int dangling = int(ends.size());
  for (int n : ends) {
    if (dangling <= dangling_target_ * length) break;
    if (degree_[std::size_t(n)] != 1) continue;
    int edge = -1;
    for (int i : incident_[std::size_t(n)])
      if (alive_[std::size_t(i)]) edge = i;
    if (edge < 0 || out_.edges[std::size_t(edge)].kept) continue;
    const NetworkEdge& e = out_.edges[std::size_t(edge)];
    const double ahead = leaving(e.points, e.from == n) + kPi;
    std::vector<Vec2> ray = ray_from(n, ahead, 0.6 * median_);
    if (auto hit = first_edge_hit(ray); hit && hit->edge != edge) {
      truncate(ray, *hit);
      // Met exactly at the hit edge's end node: joined to that node (splitting the edge there
      // would leave a one-point piece crossing what meets at the node).
      const NetworkEdge& met = out_.edges[std::size_t(hit->edge)];
      int node = -1;
      for (int m : {met.from, met.to})
        if (distance(ray.back(), out_.nodes[std::size_t(m)]) <= 1e-7 * median_) node = m;
      if (node != n && (node < 0 || !connected(n, node)) && valid(ray, true)) {
        if (node < 0) {
          link_onto(n, std::move(ray), *hit);
        } else {
          link_to(n, std::move(ray), node);
        }
        --dangling;
        continue;
      }
    }
    const int other = e.from == n ? e.to : e.from;
    if (polyline_length(e.points) < 0.5 * median_ && degree_[std::size_t(other)] >= 3) {
      index_edge(edge, false);
      alive_[std::size_t(edge)] = 0;
      --degree_[std::size_t(n)];
      --degree_[std::size_t(other)];
      ++report_.pruned;
      --dangling;
    }
  }
  // An exemplar without a single dangling end (closed cells: counties, hedged fields): the
  // ends left are pruned back to their junction whatever their length (a junction turned
  // into a bend is less unlike such an exemplar than a dead end).
  if (dangling_target_ > 0.0) return;
  for (int n : ends) trim_from(n, INFINITY);
}

// An exemplar of closed cells, none cut (no dangling end, no end on a region's boundary: its
// outermost cells are whole and their outer sides are its border), gets the same border: the
// lines cut by the region's boundary are taken out back to their junctions, so that the
// outermost cells left are whole and their outer sides, merged through the nodes that lost the
// cut line, are the output's border.
void Grower::keep_whole_cells() {
  if (!whole_cells_ || completing_) return;
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    if (!out_.on_boundary[n] || degree_[n] != 1) continue;
    const std::vector<int> inc = alive_incident(int(n));
    if (inc.size() != 1 || out_.edges[std::size_t(inc[0])].kept) continue;
    const NetworkEdge& e = out_.edges[std::size_t(inc[0])];
    const int other = e.from == int(n) ? e.to : e.from;
    index_edge(inc[0], false);
    alive_[std::size_t(inc[0])] = 0;
    --degree_[n];
    --degree_[std::size_t(other)];
    ++report_.pruned;
    const std::size_t trimmed_to = std::size_t(trim_from(other, INFINITY));
    border_node_.resize(std::max(border_node_.size(), trimmed_to + 1), 0);
    border_node_[trimmed_to] = 1;
  }
}

}  // namespace tw::network_detail
