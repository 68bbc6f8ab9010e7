// Grower: straight edges (corners, kinks) and the network as it is written.

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

// How far (median edge lengths) straighten_edges continues a corner's leg that neither its
// chord nor its removal could undo: across the open cell beside it.
constexpr double kChainCornerReach = 4.0;

// How near (median edge lengths) the lines at a node may cross a link ending on it: the float
// error of a ray passing through the node, not a gap.
constexpr double kNodeJoinSlack = 1e-3;

// A step of an output line shorter than this part of the clearance is a hair (a snapped end's
// last step), left out where the exemplar's lines are straight (Grower::straighten_edges).
constexpr double kShortStep = 0.3;

}  // namespace

std::vector<Grower::Chain> Grower::chains() const {
  const std::size_t nn = out_.nodes.size();
  std::vector<std::vector<int>> incident(nn);
  for (std::size_t i = 0; i < out_.edges.size(); ++i)
    if (alive_[i]) {
      incident[std::size_t(out_.edges[i].from)].push_back(int(i));
      incident[std::size_t(out_.edges[i].to)].push_back(int(i));
    }
  const auto passes_through = [&](int n) {
    const auto& inc = incident[std::size_t(n)];
    return inc.size() == 2 && inc[0] != inc[1] && !out_.edges[std::size_t(inc[0])].kept &&
           !out_.edges[std::size_t(inc[1])].kept;
  };
  std::vector<char> used(out_.edges.size(), 0);
  std::vector<Chain> out;
  const auto walk = [&](int start, int first) {
    Chain c;
    c.kept = out_.edges[std::size_t(first)].kept;
    c.points.push_back(out_.nodes[std::size_t(start)]);
    int at = start, edge = first;
    while (true) {
      used[std::size_t(edge)] = 1;
      c.edges.push_back(edge);
      const NetworkEdge& e = out_.edges[std::size_t(edge)];
      std::vector<Vec2> pts = e.points;
      int next = e.to;
      if (e.from != at) std::reverse(pts.begin(), pts.end()), next = e.from;
      c.points.insert(c.points.end(), pts.begin() + 1, pts.end());
      at = next;
      if (at == start || !passes_through(at) || e.kept) break;
      const auto& inc = incident[std::size_t(at)];
      const int other = inc[0] == edge ? inc[1] : inc[0];
      if (used[std::size_t(other)]) break;
      edge = other;
    }
    c.from = start;
    c.to = at;
    if (c.kept) {  // as drawn
      const NetworkEdge& e = out_.edges[std::size_t(first)];
      c.points = e.points;
      c.from = e.from;
      c.to = e.to;
    }
    out.push_back(std::move(c));
  };
  for (std::size_t n = 0; n < nn; ++n)
    if (!passes_through(int(n)))
      for (int e : incident[n])
        if (!used[std::size_t(e)]) walk(int(n), e);
  for (std::size_t e = 0; e < out_.edges.size(); ++e)
    if (alive_[e] && !used[e]) walk(out_.edges[e].from, int(e));
  return out;
}

// Where the exemplar's edges are nearly all straight (a grid's tracks, fields split by straight
// hedges), the bends the output's edges pick up (a stroke's small deflections, snapped ends
// bent, corners merged) are replaced by the edge's chord when the chord is committed under the
// same rules as any line, leaves its junctions within kStraightenDeflection of the old
// headings and meets the other lines there at no less than the exemplar's narrowest junction
// angle (nor kMinMeetingAngle; a corner's chord turned up to kStraightenDeflection off its old
// heading made Ys the exemplar has none of: the bocage's 52°, the grid's 90°): kinks always,
// corners while the output holds a larger share of bent edges than the exemplar (its few bent edges
// are corners too: a frame's).
void Grower::straighten_edges() {
  if (straight_share_ < kStraightShare) return;
  std::vector<Chain> before = chains();
  std::erase_if(before, [](const Chain& c) { return c.kept; });  // as drawn
  std::size_t bent = 0;
  for (const Chain& c : before) bent += polyline_turning(c.points) >= kStraightTurning;
  const double allowed = (1.0 - straight_share_) * double(before.size());
  // Dead ends the exemplar's rate still allows.
  int dangling = 0;
  for (std::size_t n = 0; n < out_.nodes.size(); ++n)
    dangling += degree_[n] == 1 && !out_.on_boundary[n];
  double length = 0.0;
  for (std::size_t i = 0; i < out_.edges.size(); ++i)
    if (alive_[i]) length += polyline_length(out_.edges[i].points);
  int ends_allowed = int(dangling_target_ * length) - dangling;
  // Steps shorter than kShortStep clearances (a snapped end's last hair) turn sharply over no
  // length: the exemplar's straight lines have none. `bent` still counts them (the corners'
  // pass below went on as long as before).
  for (const Chain& c : before)
    if (const std::vector<Vec2> tidy = without_short_steps(c.points);
        polyline_turning(tidy) + kStraightTurning < polyline_turning(c.points))
      replace_chain(c, tidy);
  // Jogs at a chain's ends (without_end_jogs) before the corners' pass: their corners are too
  // near a junction for a link through them to keep the rules.
  for (const Chain& c : chains())
    if (!c.kept) without_end_jogs(c);
  before = chains();
  std::erase_if(before, [](const Chain& c) { return c.kept; });
  for (const Chain& c : before)
    if (double(bent) > allowed + 0.5 && sharpest_turn(c.points) >= kCornerTurn && !on_border(c) &&
        still_a_chain(c) &&
        (straighten(c) || remove_corner(c, ends_allowed) || link_chain_corner(c)))
      --bent;
  // Kinks always (the junctions a removed corner left are straight through now).
  straighten_kinks();
}

void Grower::straighten_kinks() {
  // Hair steps first (a link or a merge may have left one at a node since straighten_edges).
  for (const Chain& c : chains())
    if (const std::vector<Vec2> tidy = without_short_steps(c.points);
        !c.kept && polyline_turning(tidy) + kStraightTurning < polyline_turning(c.points))
      replace_chain(c, tidy);
  for (const Chain& c : chains())
    if (!c.kept && sharpest_turn(c.points) < kCornerTurn && polyline_turning(c.points) > 0.0)
      straighten(c);
}

// The outermost cells' sides merged through the nodes that lost a cut line are the exemplar's
// own kind of bend (its border's): they are kept. Nodes made later (a corner linked on) are
// past the end of border_node_ and never on the border.
bool Grower::on_border(const Chain& c) const {
  for (int e : c.edges)
    for (int n : {out_.edges[std::size_t(e)].from, out_.edges[std::size_t(e)].to})
      if (n != c.from && n != c.to && std::size_t(n) < border_node_.size() &&
          border_node_[std::size_t(n)])
        return true;
  return false;
}

// Whether chain c is as it was found: its edges alive, the nodes it passes of degree 2 still
// (a corner linked on before it may have ended on one of them, or split one of its edges).
bool Grower::still_a_chain(const Chain& c) const {
  for (int e : c.edges) {
    if (!alive_[std::size_t(e)]) return false;
    for (int n : {out_.edges[std::size_t(e)].from, out_.edges[std::size_t(e)].to})
      if (n != c.from && n != c.to && degree_[std::size_t(n)] != 2) return false;
  }
  return true;
}

// Points p with those less than kShortStep clearances past the last one kept, or short of the
// end, left out (the ends stay).
std::vector<Vec2> Grower::without_short_steps(const std::vector<Vec2>& p) const {
  std::vector<Vec2> out{p.front()};
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    if (distance(p[k], out.back()) >= kShortStep * clearance_ &&
        distance(p[k], p.back()) >= kShortStep * clearance_)
      out.push_back(p[k]);
  out.push_back(p.back());
  return out;
}

// A chain's first or last step shorter than the shortest edge growth places (min_piece_: a
// jog, where a line was laid a few metres beside the junction it ends at) is left out, the
// line going straight from its junction to the step's far end, where it then meets the other
// lines there at kMinMeetingAngle or more and is committed under the rules it kept. A right
// angle over a few metres is a curvature no straight exemplar has (the grid's output: one
// 17 m corner gave most of its curvature distance of 0.83 at seed 1).
bool Grower::without_end_jogs(const Chain& c) {
  std::vector<Vec2> p = c.points;
  if (p.size() < 3 || c.from == c.to) return false;
  const bool first = distance(p[0], p[1]) < min_piece_;
  if (distance(p[p.size() - 1], p[p.size() - 2]) < min_piece_) p.erase(p.end() - 2);
  if (first && p.size() >= 3) p.erase(p.begin() + 1);
  if (p.size() == c.points.size() || polyline_length(p) < min_piece_) return false;
  for (int end = 0; end < 2; ++end) {
    const int n = end == 0 ? c.from : c.to;
    const double h = leaving(p, end == 0);
    for (int other : alive_incident(n)) {
      if (std::find(c.edges.begin(), c.edges.end(), other) != c.edges.end()) continue;
      const NetworkEdge& e = out_.edges[std::size_t(other)];
      if (std::abs(wrap(h - leaving(e.points, e.from == n))) < kMinMeetingAngle) return false;
    }
  }
  return replace_chain(c, p);
}

double Grower::sharpest_turn(const std::vector<Vec2>& p) {
  double sharpest = 0.0;
  for (std::size_t k = 1; k + 1 < p.size(); ++k)  // as polyline_turning (repeated points)
    sharpest = std::max(sharpest, polyline_turning({p[k - 1], p[k], p[k + 1]}));
  return sharpest;
}

// How many dead ends taking chain `c` off leaves at its end node n (0 or 1), or -1 when that
// is not allowed: n is left a junction still, a line going straight through it (within a
// stroke's deflection) or a dead end; a cut end on the boundary goes with its line.
int Grower::ends_left_at(int n, const Chain& c) const {
  if (out_.on_boundary[std::size_t(n)]) return 0;
  std::vector<int> rest;
  for (int e : alive_incident(n))
    if (std::find(c.edges.begin(), c.edges.end(), e) == c.edges.end()) rest.push_back(e);
  if (rest.size() >= 3) return 0;
  if (rest.size() == 1) return 1;
  if (rest.size() != 2) return -1;
  const NetworkEdge& a = out_.edges[std::size_t(rest[0])];
  const NetworkEdge& b = out_.edges[std::size_t(rest[1])];
  if (a.kept || b.kept) return -1;
  const double ha = leaving(a.points, a.from == n), hb = leaving(b.points, b.from == n);
  return std::abs(wrap(ha - hb - kPi)) > kStrokeDeflection ? -1 : 0;
}

void Grower::take_off(const Chain& c) {
  for (int e : c.edges) {
    index_edge(e, false);
    alive_[std::size_t(e)] = 0;
    --degree_[std::size_t(out_.edges[std::size_t(e)].from)];
    --degree_[std::size_t(out_.edges[std::size_t(e)].to)];
    ++report_.pruned;
  }
  forget_passed_nodes(c);
  if (cell_cycles_) cell_cycles_->line_taken_off(c.edges);
}

// A corner its chord cannot replace is taken out whole, junction to junction, when both its
// end nodes allow it (ends_left_at) and the dead ends left are within the exemplar's rate
// (`ends_allowed`, spent); else one leg is taken off at the corner (the shorter first), the
// corner becoming a dead end, the other leg kept as it lies.
bool Grower::remove_corner(const Chain& c, int& ends_allowed) {
  if (c.from == c.to) return false;
  const int at_from = ends_left_at(c.from, c), at_to = ends_left_at(c.to, c);
  if (at_from >= 0 && at_to >= 0 && at_from + at_to <= ends_allowed) {
    ends_allowed -= at_from + at_to;
    take_off(c);
    return true;
  }
  const std::vector<Vec2>& p = c.points;
  std::size_t corner = 0;
  double sharpest = 0.0;
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    if (const double t = polyline_turning({p[k - 1], p[k], p[k + 1]}); t > sharpest)
      sharpest = t, corner = k;
  if (corner == 0) return false;
  const double from_leg = polyline_length({p.begin(), p.begin() + long(corner) + 1});
  for (int side : from_leg <= 0.5 * polyline_length(p) ? std::array{0, 1} : std::array{1, 0}) {
    const int ends = (side == 0 ? at_from : at_to);
    if (ends < 0 || ends + 1 > ends_allowed) continue;
    std::vector<Vec2> kept = side == 0 ? std::vector<Vec2>(p.begin() + long(corner), p.end())
                                       : std::vector<Vec2>(p.begin(), p.begin() + long(corner) + 1);
    if (polyline_length(kept) < min_piece_ || sharpest_turn(kept) >= kCornerTurn) continue;
    ends_allowed -= ends + 1;
    take_off(c);
    const int dead_end = add_node(p[corner]);
    NetworkEdge e;
    e.from = side == 0 ? dead_end : c.from;
    e.to = side == 0 ? c.to : dead_end;
    e.points = std::move(kept);
    add_edge(std::move(e));
    return true;
  }
  return false;
}

// A corner its chord cannot replace nor its removal undo, at a node the chain passes (degree
// 2), becomes a T-junction as close_corners makes one, but reaching farther (the cell beyond
// is still open there): one leg continued straight through it onto the line ahead or to the
// region's boundary. Both legs are then edges of their own, straight.
bool Grower::link_chain_corner(const Chain& c) {
  // A corner inside one edge (a copied exemplar line's own corner, as its frame's) is made a
  // node first: one that stays of degree 2 is merged away as the network is written (finish).
  // (The edge's first such corner: the edge ends there now, and c.edges still holds it.)
  for (int e : c.edges) {
    const std::vector<Vec2> p = out_.edges[std::size_t(e)].points;
    for (std::size_t k = 1; k + 1 < p.size(); ++k)
      if (polyline_turning({p[k - 1], p[k], p[k + 1]}) >= kCornerTurn &&
          distance(p[k], p.front()) >= clearance_ && distance(p[k], p.back()) >= clearance_) {
        split_edge(e, int(k), p[k]);
        break;
      }
  }
  for (int e : c.edges)
    for (int n : {out_.edges[std::size_t(e)].from, out_.edges[std::size_t(e)].to}) {
      if (n == c.from || n == c.to || degree_[std::size_t(n)] != 2 ||
          out_.on_boundary[std::size_t(n)])
        continue;
      const std::vector<int> legs = alive_incident(n);
      if (legs.size() != 2) continue;
      double h[2];
      for (int k = 0; k < 2; ++k) {
        const NetworkEdge& leg = out_.edges[std::size_t(legs[std::size_t(k)])];
        h[k] = leaving(leg.points, leg.from == n);
      }
      if (std::abs(wrap(h[0] - h[1] - kPi)) < kCornerTurn) continue;
      for (int k = 0; k < 2; ++k)
        if (link_ahead(n, h[k] + kPi, kChainCornerReach * median_, legs[std::size_t(1 - k)]) ||
            link_to_boundary(n, h[k] + kPi, kChainCornerReach * median_) ||
            link_to_passed_node(n, h[k] + kPi, kChainCornerReach * median_))
          return true;
    }
  return false;
}

// Node n joined straight along `heading` onto a node of degree 2 that the ray ends within the
// clearance of (a line's end meeting another's side there, or another corner facing this one):
// it becomes a T, where link_ahead refuses to end so near a node. Where the exemplar's cells
// are closed and straight and its lines end in Ts (cells_end_in_ts_: a field's one bent edge
// weighs more on its curvature than a junction of four on its degrees), also onto a junction
// of three, which becomes one of four; elsewhere not (the grid's junction angles suffered at
// seed 3). Never shorter than a piece.
bool Grower::link_to_passed_node(int n, double heading, double reach) {
  const Vec2 p = out_.nodes[std::size_t(n)];
  std::vector<Vec2> ray = ray_from(n, heading, reach);
  const auto hit = first_edge_hit(ray);
  if (!hit) return false;
  truncate(ray, *hit);
  const NetworkEdge& e = out_.edges[std::size_t(hit->edge)];
  for (int m : {e.from, e.to}) {
    const bool joinable =
        degree_[std::size_t(m)] == 2 || (cells_end_in_ts_ && degree_[std::size_t(m)] == 3);
    if (m == n || !joinable || out_.on_boundary[std::size_t(m)] ||
        distance(ray.back(), out_.nodes[std::size_t(m)]) >= clearance_ || connected(n, m))
      continue;
    std::vector<Vec2> link{p, out_.nodes[std::size_t(m)]};
    if (polyline_length(link) < min_piece_ ||
        std::abs(wrap(leaving(link, true) - heading)) > kStrokeDeflection ||
        !valid(link, true, Spacing::grown, kNodeJoinSlack * median_))
      continue;
    link_to(n, std::move(link), m);
    return true;
  }
  return false;
}

// The nodes a chain passed through, left without edges, are no seeds to keep clear of.
void Grower::forget_passed_nodes(const Chain& c) {
  for (int e : c.edges) {
    const NetworkEdge& edge = out_.edges[std::size_t(e)];
    for (int n : {edge.from, edge.to})
      if (n != c.from && n != c.to && degree_[std::size_t(n)] == 0)
        nodes_.remove(NodeValue{to_bg(out_.nodes[std::size_t(n)]), n});
  }
}

bool Grower::straighten(const Chain& c) {
  const std::vector<Vec2> chord{c.points.front(), c.points.back()};
  return polyline_length(chord) >= min_piece_ &&
         ends_meet_lines(c, chord, std::max(kMinMeetingAngle, narrowest_junction_)) &&
         replace_chain(c, chord);
}

// Whether `line`, to replace chain c (same ends), leaves its junctions within
// kStraightenDeflection of the chain's headings there and meets the other lines there at
// `min_angle` or more (no other edge joining the same two nodes).
bool Grower::ends_meet_lines(const Chain& c, const std::vector<Vec2>& line,
                             double min_angle) const {
  for (int end = 0; end < 2; ++end) {
    const int n = end == 0 ? c.from : c.to;
    const double old_heading = leaving(c.points, end == 0), new_heading = leaving(line, end == 0);
    if (std::abs(wrap(new_heading - old_heading)) > kStraightenDeflection) return false;
    for (int other : alive_incident(n)) {
      if (std::find(c.edges.begin(), c.edges.end(), other) != c.edges.end()) continue;
      const NetworkEdge& e = out_.edges[std::size_t(other)];
      if ((e.from == c.from && e.to == c.to) || (e.from == c.to && e.to == c.from)) return false;
      const double h = leaving(e.points, e.from == n);
      if (std::abs(wrap(h - new_heading)) < min_angle) return false;
    }
  }
  return true;
}

// Chain c replaced by `line` (same ends) when that is committed under the rules the line it
// replaces kept: a copy of exemplar lines (quilt, layout) keeps the exemplar's own spacing near
// its junctions, a grown piece the clearance there too.
bool Grower::replace_chain(const Chain& c, const std::vector<Vec2>& line) {
  for (int e : c.edges) index_edge(e, false);
  if (!valid(line, true) && (valid(c.points, true) || !valid(line, true, Spacing::laid_out))) {
    for (int e : c.edges) index_edge(e, true);
    return false;
  }
  for (int e : c.edges) {
    alive_[std::size_t(e)] = 0;
    --degree_[std::size_t(out_.edges[std::size_t(e)].from)];
    --degree_[std::size_t(out_.edges[std::size_t(e)].to)];
  }
  forget_passed_nodes(c);
  NetworkEdge straight;
  straight.from = c.from;
  straight.to = c.to;
  straight.points = line;
  add_edge(std::move(straight));
  return true;
}

// Alive edges, nodes of degree 2 between grown edges merged (chains), unused nodes dropped.
Network Grower::finish() {
  Network net;
  std::vector<int> id(out_.nodes.size(), -1);
  const auto keep = [&](int n) {
    if (id[std::size_t(n)] < 0) {
      id[std::size_t(n)] = int(net.nodes.size());
      net.nodes.push_back(out_.nodes[std::size_t(n)]);
      net.on_boundary.push_back(out_.on_boundary[std::size_t(n)]);
    }
    return id[std::size_t(n)];
  };
  for (Chain& c : chains()) {
    NetworkEdge merged = out_.edges[std::size_t(c.edges.front())];
    merged.points = std::move(c.points);
    merged.from = keep(c.from);
    merged.to = keep(c.to);
    net.edges.push_back(std::move(merged));
  }
  return net;
}

}  // namespace tw::network_detail
