// Grower: the network so far (nodes, edges, their index) and the rules a line keeps to be placed.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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

// Intersection parameters of segments pq and ab (proper or touching), or false when parallel.
bool segment_hit(Vec2 p, Vec2 q, Vec2 a, Vec2 b, double& t, double& u) {
  const Vec2 r = q - p, s = b - a;
  const double denom = cross(r, s);
  if (std::abs(denom) <= 1e-12 * (dot(r, r) + dot(s, s))) return false;
  t = cross(a - p, s) / denom;
  u = cross(a - p, r) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

// Whether segments pq and ab run along each other for more than `eps`: two of their four ends
// lie within `eps` of the other segment and more than `eps` apart. Boost's intersection of two
// segments a rounding error off collinear may give a single point (at a joint, where they meet
// anyway) rather than their overlap.
bool runs_along(Vec2 p, Vec2 q, Vec2 a, Vec2 b, double eps) {
  std::array<Vec2, 4> on;
  std::size_t n = 0;
  for (Vec2 x : {a, b})
    if (distance_to_segment(x, p, q) <= eps) on[n++] = x;
  for (Vec2 x : {p, q})
    if (distance_to_segment(x, a, b) <= eps) on[n++] = x;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (distance(on[i], on[j]) > eps) return true;
  return false;
}

// A point this many units in the last place of its coordinates from a vertex is the vertex,
// rounded (a hit's point computed along the line that hit it).
constexpr double kRoundingUlps = 16.0;

}  // namespace

int Grower::add_node(Vec2 p) {
  const int id = int(out_.nodes.size());
  out_.nodes.push_back(p);
  out_.on_boundary.push_back(0);
  degree_.push_back(0);
  planned_.push_back(0);
  incident_.emplace_back();
  stubs_of_.emplace_back();
  nodes_.insert({to_bg(p), id});
  return id;
}

void Grower::index_edge(int id, bool insert) {
  const auto& pts = out_.edges[std::size_t(id)].points;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const SegValue v{BgSegment(to_bg(pts[k]), to_bg(pts[k + 1])), id};
    if (insert)
      segments_.insert(v);
    else
      segments_.remove(v);
  }
}

int Grower::add_edge(NetworkEdge e) {
  ++degree_[std::size_t(e.from)];
  ++degree_[std::size_t(e.to)];
  const int id = int(out_.edges.size());
  incident_[std::size_t(e.from)].push_back(id);
  if (e.to != e.from) incident_[std::size_t(e.to)].push_back(id);
  count_edge_bearing(e.points, 1.0);
  out_.edges.push_back(std::move(e));
  alive_.push_back(1);
  index_edge(id, true);
  return id;
}

// The output's edges by chord bearing, as the statistics count them (a T splits an edge in
// two, a stroke's junctions passed through split it): what opened_cost steers by.
void Grower::count_edge_bearing(const std::vector<Vec2>& pts, double count) {
  if (pts.size() < 2 || pts.back() == pts.front()) return;
  edge_bearing_[std::size_t(bearing_bin(pts.back() - pts.front()))] += count;
  edge_count_ += count;
  bearing_cdf_.add_output(pts.back() - pts.front(), count);
}

// Splits edge `id` at `p` on its segment `seg`: the new node.
int Grower::split_edge(int id, int seg, Vec2 p) {
  // A hit at a vertex, its point rounded a few units in the last place off it, splits the edge
  // at the vertex: kept beside p, the vertex would leave a step of 1e-14 m that `valid` never
  // saw, lying on the line that ends at p (the safety net finds the two overlapping). The
  // callers end their lines on the node, where it is.
  const double hair = kRoundingUlps * std::numeric_limits<double>::epsilon() *
                      std::max({std::abs(p.x), std::abs(p.y), median_});
  for (std::size_t k : {std::size_t(seg), std::size_t(seg) + 1})
    if (k > 0 && k + 1 < out_.edges[std::size_t(id)].points.size() &&
        distance(out_.edges[std::size_t(id)].points[k], p) <= hair)
      p = out_.edges[std::size_t(id)].points[k];
  index_edge(id, false);
  const int node = add_node(p);
  NetworkEdge& e = out_.edges[std::size_t(id)];
  count_edge_bearing(e.points, -1.0);
  NetworkEdge second;
  second.from = node;
  second.to = e.to;
  second.kept = e.kept;
  second.fid = e.fid;
  second.points.push_back(p);
  for (std::size_t k = std::size_t(seg) + 1; k < e.points.size(); ++k)
    if (!(e.points[k] == p)) second.points.push_back(e.points[k]);
  e.points.resize(std::size_t(seg) + 1);
  if (!(e.points.back() == p)) e.points.push_back(p);
  auto& at_end = incident_[std::size_t(e.to)];
  at_end.erase(std::remove(at_end.begin(), at_end.end(), id), at_end.end());
  e.to = node;
  count_edge_bearing(e.points, 1.0);
  incident_[std::size_t(node)].push_back(id);
  index_edge(id, true);
  if (second.points.size() < 2) second.points.push_back(p);
  --degree_[std::size_t(second.to)];  // add_edge counts both of its ends
  add_edge(std::move(second));
  degree_[std::size_t(node)] = 2;
  if (cell_cycles_) cell_cycles_->edge_split(id, int(out_.edges.size()) - 1);
  return node;
}

// The first place where `pts` meets the network, past its start.
std::optional<Hit> Grower::first_edge_hit(const std::vector<Vec2>& pts) const {
  std::vector<SegValue> near;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const BgSegment s(to_bg(pts[k]), to_bg(pts[k + 1]));
    near.clear();
    BgBox box;
    bg::envelope(s, box);
    segments_.query(bgi::intersects(box), std::back_inserter(near));
    std::optional<Hit> best;
    for (const SegValue& v : near) {
      const Vec2 a = vec(v.first.first), b = vec(v.first.second);
      double t, u;
      if (!segment_hit(pts[k], pts[k + 1], a, b, t, u)) continue;
      if (k == 0 && t * distance(pts[0], pts[1]) < 1e-9 * median_) continue;  // the start
      if (!best || t < best->t) {
        const auto& e = out_.edges[std::size_t(v.second)].points;
        int seg = 0;
        for (std::size_t j = 0; j + 1 < e.size(); ++j)
          if (e[j] == a && e[j + 1] == b) seg = int(j);
        best = Hit{k, t, lerp(pts[k], pts[k + 1], t), v.second, seg};
      }
    }
    if (best) return best;
  }
  return std::nullopt;
}

std::optional<Hit> Grower::first_boundary_hit(const std::vector<Vec2>& pts) const {
  std::vector<BgSegment> near;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const BgSegment s(to_bg(pts[k]), to_bg(pts[k + 1]));
    BgBox box;
    bg::envelope(s, box);
    near.clear();
    boundary_.query(bgi::intersects(box), std::back_inserter(near));
    std::optional<Hit> best;
    for (const BgSegment& b : near) {
      double t, u;
      if (!segment_hit(pts[k], pts[k + 1], vec(b.first), vec(b.second), t, u)) continue;
      if (k == 0 && t * distance(pts[0], pts[1]) < 1e-9 * median_) continue;
      if (!best || t < best->t) best = Hit{k, t, lerp(pts[k], pts[k + 1], t), -1, -1};
    }
    if (best) return best;
  }
  return std::nullopt;
}

// Whether the candidate may be placed: no crossing but at its joints (its start, and its end
// when that is on the network), the clearance elsewhere, inside the region, off forbidden
// cells.
// `spacing` (Spacing): how near other lines a copy of exemplar lines may come.
// `joint_slack`: a crossing this close to a joint, with a segment that ends at that joint,
// counts as meeting there (a line copied by a translation meets its continuation nearly
// collinearly, where the rounding of the copy puts the crossing a hair off the node).
bool Grower::valid(const std::vector<Vec2>& pts, bool end_joint, Spacing spacing,
                   double joint_slack) {
  const bool own_clearance = spacing == Spacing::grown;
  const Vec2 start = pts.front(), end = pts.back();
  const double eps = 1e-7 * median_;
  std::vector<SegValue> near;
  std::vector<BgPoint> common;
  // The candidate itself is simple (a bent or truncated piece could touch itself), and its
  // ends keep the clearance from its own other segments (an end on itself is a crossing that
  // no other edge would show).
  if (pts.size() > 3) {
    BgLine line;
    for (Vec2 p : pts) bg::append(line, to_bg(p));
    if (!bg::is_simple(line)) return false;
  }
  for (std::size_t k = 0; own_clearance && k + 2 < pts.size(); ++k)
    if (distance_to_segment(end, pts[k], pts[k + 1]) < clearance_) return false;
  for (std::size_t k = 1; own_clearance && k + 1 < pts.size(); ++k)
    if (distance_to_segment(start, pts[k], pts[k + 1]) < clearance_) return false;
  std::vector<Vec2> joints{start};
  if (end_joint) joints.push_back(end);
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const Vec2 a = pts[k], b = pts[k + 1];
    const BgSegment s(to_bg(a), to_bg(b));
    const BgBox box({std::min(a.x, b.x) - clearance_ - eps, std::min(a.y, b.y) - clearance_ - eps},
                    {std::max(a.x, b.x) + clearance_ + eps, std::max(a.y, b.y) + clearance_ + eps});
    near.clear();
    segments_.query(bgi::intersects(box), std::back_inserter(near));
    // The part of the segment outside the clearance discs of the joints: lines meeting at a
    // junction are necessarily close to each other there.
    Vec2 ta = a, tb = b;
    bool kept = true;
    for (Vec2 j : joints) kept = kept && trim_outside_disc(ta, tb, j, clearance_);
    const BgSegment trimmed(to_bg(ta), to_bg(tb));
    for (const SegValue& v : near) {
      common.clear();
      bg::intersection(s, v.first, common);
      if (!common.empty()) {
        if (common.size() > 1 && bg::distance(common[0], common[1]) > eps) return false;
        const Vec2 x = vec(common[0]);
        const auto meets = [&](Vec2 joint) {
          if (distance(x, joint) <= eps) return true;
          return distance(x, joint) <= joint_slack && (distance(vec(v.first.first), joint) <= eps ||
                                                       distance(vec(v.first.second), joint) <= eps);
        };
        const bool at_start = k == 0 && meets(start);
        const bool at_end = end_joint && k + 2 == pts.size() && meets(end);
        if (!at_start && !at_end) return false;
        // Nor along a line from the joint (Boost gives one point for two segments a rounding
        // error off collinear).
        if (runs_along(a, b, vec(v.first.first), vec(v.first.second), eps)) return false;
        continue;
      }
      // Segments meeting at a joint (its edges, the edge a T-junction splits) are exempt.
      const Vec2 ea = vec(v.first.first), eb = vec(v.first.second);
      bool at_joint = false;
      for (Vec2 j : joints) at_joint = at_joint || distance_to_segment(j, ea, eb) <= eps;
      if (at_joint) {
        if (runs_along(a, b, ea, eb, eps)) return false;
        continue;
      }
      // A laid-out line keeps the exemplar's spacing from the lines it meets at its joints:
      // their part within the joint's clearance is exempt too, as the candidate's is (two
      // lines meeting at right angles are just a clearance apart outside it).
      Vec2 sa = ea, sb = eb;
      bool stored_outside = true;
      if (spacing == Spacing::laid_out && edge_meets(v.second, joints))
        for (Vec2 j : joints)
          if (distance_to_segment(j, sa, sb) < clearance_)
            stored_outside = stored_outside && trim_outside_disc(sa, sb, j, clearance_);
      if (kept && stored_outside &&
          bg::distance(trimmed, BgSegment(to_bg(sa), to_bg(sb))) < clearance_)
        return false;
      // The other way round: the candidate's part near a joint is exempt only from the lines
      // meeting there and from what lies within the clearance of the joint, not from another
      // line's corner farther off that it would graze (a grown piece leaving a junction 6 m
      // from a free end passed 5.8 m from it with a clearance of 6). Copies of exemplar lines
      // (not `Spacing::grown`) keep the exemplar's own spacing.
      Vec2 va = ea, vb = eb;
      bool stored_kept = true;
      // A line aimed at the joint and ending at most a median edge short of its disc counts
      // as reaching the disc: a candidate leaving the joint across that gap would cut a sliver
      // off the cell the line's continuation closes.
      for (Vec2 j : joints) {
        prolong_to_disc(va, vb, j, clearance_, median_);
        stored_kept = stored_kept && trim_outside_disc(va, vb, j, clearance_);
      }
      if (own_clearance && stored_kept &&
          bg::distance(s, BgSegment(to_bg(va), to_bg(vb))) < clearance_ &&
          !edge_meets(v.second, joints))
        return false;
    }
  }
  // Nodes without edges yet (seeds whose stubs are still to be retried) are in no segment
  // index: a candidate ending on or passing by one would meet its later edges off a node.
  std::vector<NodeValue> seeds;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const Vec2 a = pts[k], b = pts[k + 1];
    const BgBox box({std::min(a.x, b.x) - clearance_ - eps, std::min(a.y, b.y) - clearance_ - eps},
                    {std::max(a.x, b.x) + clearance_ + eps, std::max(a.y, b.y) + clearance_ + eps});
    seeds.clear();
    nodes_.query(bgi::intersects(box), std::back_inserter(seeds));
    for (const NodeValue& n : seeds) {
      const Vec2 p = vec(n.first);
      if (degree_[std::size_t(n.second)] > 0 || distance(p, start) <= eps ||
          (end_joint && distance(p, end) <= eps))
        continue;
      if (distance_to_segment(p, a, b) < clearance_) return false;
    }
  }
  for (std::size_t k = 1; k < pts.size(); ++k)
    if (!inside_region(pts[k])) {
      ++report_.rejected_region;
      return false;
    }
  if (auto wall = first_boundary_hit(pts); wall && distance(wall->point, end) > 1e-6 * median_) {
    ++report_.rejected_region;
    return false;
  }
  if (enters_forbidden(pts)) {
    ++report_.rejected_forbidden;
    return false;
  }
  return true;
}

// Whether edge `id` ends at one of `joints` or passes through it (the edge a T splits).
bool Grower::edge_meets(int id, const std::vector<Vec2>& joints) const {
  const double eps = 1e-7 * median_;
  const std::vector<Vec2>& pts = out_.edges[std::size_t(id)].points;
  for (Vec2 j : joints)
    for (std::size_t k = 0; k + 1 < pts.size(); ++k)
      if (distance_to_segment(j, pts[k], pts[k + 1]) <= eps) return true;
  return false;
}

// Whether a new node at p would keep the clearance from every line.
bool Grower::clear_of_lines(Vec2 p) const {
  std::vector<SegValue> near;
  segments_.query(bgi::nearest(to_bg(p), 1), std::back_inserter(near));
  return near.empty() || bg::distance(near[0].first, to_bg(p)) >= clearance_;
}

// A placed line counted in the histograms growth steers by.
void Grower::count_line(const std::vector<Vec2>& pts) {
  have_bearing_[std::size_t(bearing_bin(pts.back() - pts.front()))] += 1.0;
  have_length_[std::size_t(length_bin(polyline_length(pts)))] += 1.0;
  placed_ += 1.0;
  grown_length_ += polyline_length(pts);
}

// The parts of a line inside the region; an end cut by the region's boundary is pulled a
// hair inside (as a grown piece's is).
std::vector<std::vector<Vec2>> Grower::inside_parts(std::vector<Vec2> pts) const {
  bool whole = true;
  for (Vec2 p : pts) whole = whole && inside_region(p);
  if (whole && !first_boundary_hit(pts)) return {std::move(pts)};
  BgLine line;
  for (Vec2 p : pts) bg::append(line, to_bg(p));
  BgLines parts;
  bg::intersection(line, region_, parts);
  std::vector<std::vector<Vec2>> out;
  for (const BgLine& part : parts) {
    std::vector<Vec2> q;
    for (const BgPoint& p : part)
      if (q.empty() || !(vec(p) == q.back())) q.push_back(vec(p));
    if (q.size() < 2) continue;
    for (int end = 0; end < 2; ++end) {
      Vec2& p = end == 0 ? q.front() : q.back();
      const Vec2 inner = end == 0 ? q[1] : q[q.size() - 2];
      if (p == pts.front() || p == pts.back() || !near_boundary(p)) continue;
      p = p + (inner - p) * std::min(0.5, 1e-9 * median_ / std::max(distance(inner, p), 1e-300));
    }
    out.push_back(std::move(q));
  }
  return out;
}

// Commits a quilt line when it keeps the rules; its ends join the nodes already at their
// exact places (the block's junctions, a stitched seam).
bool Grower::place_line(std::vector<Vec2> pts, double joint_slack, Spacing spacing) {
  if (pts.size() < 2 || polyline_length(pts) <= 1e-9 * median_) return false;
  const auto existing = [&](Vec2 p) {
    const auto it = node_at_.find({p.x, p.y});
    return it == node_at_.end() ? -1 : it->second;
  };
  int ends[2] = {existing(pts.front()), existing(pts.back())};
  const bool ring = pts.front() == pts.back();
  for (int k = 0; k < 2; ++k) {
    if (ends[k] >= 0) continue;
    // A new node keeps the clearance from every line (it may not lie on one).
    if (!clear_of_lines(k == 0 ? pts.front() : pts.back())) return false;
  }
  if (ring && pts.size() < 4) return false;
  if (!valid(pts, true, spacing, joint_slack)) return false;
  for (int k = 0; k < 2; ++k) {
    if (ends[k] >= 0) continue;
    if (k == 1 && ring) {
      ends[1] = ends[0];
      continue;
    }
    const Vec2 p = k == 0 ? pts.front() : pts.back();
    ends[k] = add_node(p);
    node_at_[{p.x, p.y}] = ends[k];
    if (near_boundary(p)) out_.on_boundary[std::size_t(ends[k])] = 1;
  }
  NetworkEdge e;
  e.from = ends[0];
  e.to = ends[1];
  e.points = std::move(pts);
  add_edge(std::move(e));
  ++report_.placed;
  return true;
}

}  // namespace tw::network_detail
