#include "network/growth.hpp"

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

namespace tw {

namespace network_detail {

// The weight of a piece's turn from its exemplar heading (0..1) in a candidate's cost.
constexpr double kTurnWeight = 0.6;

// The gap, in clearances, that a piece ending alone in the exemplar keeps from the line it
// meets when it is kept dangling (three: a clear gap, not a near miss).
constexpr double kDanglingGap = 3.0;

// The weight of a candidate's pull on the output's bearing distribution towards the exemplar's
// (BearingCdf::step_cost, about -1..1): it picks among candidates of near-equal cost. 0.3 met the
// most targets (seeds 1-6 of 0, 0.15, 0.3, 0.5, 0.7, 1 and 3; 0.3, 0.4, 0.5 also seeds 7-9);
// from 1 up the grid's curvature and the stream trees' cell areas suffer.
constexpr double kBearingMatchWeight = 0.3;

void Grower::add_partial(const Network& partial) {
  completing_ = !partial.edges.empty();
  std::vector<int> id(partial.nodes.size());
  for (std::size_t n = 0; n < partial.nodes.size(); ++n) id[n] = add_node(partial.nodes[n]);
  for (const NetworkEdge& e : partial.edges) {
    NetworkEdge copy = e;
    copy.from = id[std::size_t(e.from)];
    copy.to = id[std::size_t(e.to)];
    copy.kept = true;
    add_edge(std::move(copy));
  }
  const std::vector<int> degree = out_.degrees();
  for (const NetworkEdge& e : partial.edges) {
    for (int end = 0; end < 2; ++end) {
      const int n = id[std::size_t(end == 0 ? e.from : e.to)];
      if (degree[std::size_t(n)] != 1) continue;
      if (near_boundary(out_.nodes[std::size_t(n)])) {
        out_.on_boundary[std::size_t(n)] = 1;
        continue;
      }
      // A dangling end of the drawing goes on straight.
      planned_[std::size_t(n)] = 2;
      push_stub(n, leaving(e.points, end == 0) + kPi);
    }
  }
}

Network Grower::run(Mode mode) {
  report_.quilted = mode == Mode::quilt;
  if (mode == Mode::quilt) {
    quilt();
    drain();  // a partial network's open ends, when quilting was asked for anyway
  } else {
    if (mode == Mode::layout) report_.laid_out = lay_out_long_strokes();
    drain();
    seed_lattice();
    retry_failed();
    close_corners();
  }
  close_dangling_ends();
  keep_whole_cells();
  straighten_edges();
  {
    CellCycles cells(out_, alive_, incident_);
    cell_cycles_ = &cells;
    split_large_cells(cells);
    const bool merged = merge_small_cells(cells);
    cell_cycles_ = nullptr;
    if (merged) straighten_kinks();
  }
  ease_sharp_bends();
  prune_twigs_for_bearings();
  shift_junctions_for_bearings();
  return finish();
}

double Grower::outcome_cost(const Outcome& o) const {
  const Vec2 chord = o.line.back() - o.line.front();
  double cost = excess(have_bearing_, placed_, target_bearing_, std::size_t(bearing_bin(chord)));
  cost += excess(have_length_, placed_, target_length_,
                 std::size_t(length_bin(polyline_length(o.line))));
  if (o.degree > 0)
    cost += 1.5 * excess(have_degree_, junction_count_, target_degree_,
                         std::size_t(std::min(o.degree, 6)));
  return cost;
}

// The lines a free end's new junction will grow, by the bearing histogram: a piece whose
// junction opens stubs where the output already has more than the exemplar's share of edges
// costs more (the proportions of a grid's two orientations follow which junctions are made,
// not which piece a stub takes: every piece is turned to the stub's heading). Only where the
// exemplar's edges run at few orientations: elsewhere it rewards bent pieces, whose ends
// point their stubs anywhere (the counties' curvature tripled).
//
// In a forest (its lines end free) the same holds of every branch: its bearing is its stub's,
// within the bends of the piece that takes it, so a branch junction's stubs are steered by the
// output's cumulative bearing distribution (BearingCdf) rather than by the 15° histogram.
double Grower::opened_cost(const Outcome& o, const Piece& piece) const {
  if ((!few_orientations_ && !forest_) || o.how.kind != Ending::Kind::free ||
      piece.end_turns.empty())
    return 0.0;
  const double arrive = leaving(o.line, false) + kPi;
  double cost = 0.0;
  for (double turn : piece.end_turns) {
    const double h = arrive + turn;
    const Vec2 towards{std::cos(h), std::sin(h)};
    cost += few_orientations_ ? kOpenedWeight * excess(edge_bearing_, edge_count_, target_bearing_,
                                                       std::size_t(bearing_bin(towards)))
                              : kForestOpenedWeight * bearing_cdf_.step_cost(towards);
  }
  return cost / double(piece.end_turns.size());
}

// `retry`: a stub that found nothing the first time, tried again once the region is covered
// with more candidates and a straight link onto the network ahead (a junction left short of
// its degree would become a bend or a dangling end).
void Grower::grow_stub(const Stub& stub, bool retry) {
  if (!retry) {
    if (cancelled_[std::size_t(stub.id)]) return;
    cancelled_[std::size_t(stub.id)] = 1;
    ++report_.stubs;
  }
  const Vec2 origin = out_.nodes[std::size_t(stub.node)];
  std::optional<Outcome> best;
  const Piece* best_piece = nullptr;
  Piece link;
  if (retry) {
    link.points = {{0.0, 0.0}, {1.5 * median_, 0.0}};
    link.length = 1.5 * median_;
    link.heading = stub.heading - turn_;
    if (auto o = evaluate(
            stub, link,
            {origin, origin + Vec2{std::cos(stub.heading), std::sin(stub.heading)} * link.length});
        o && (o->how.kind == Ending::Kind::node || o->how.kind == Ending::Kind::edge)) {
      o->cost = outcome_cost(*o);
      best = std::move(o), best_piece = &link;
    }
  }
  if (stub.own_piece >= 0 && !retry) {
    // A laid-out junction takes the exemplar's own piece there when it fits (the cells
    // between the long strokes as the exemplar has them); the drawn candidates otherwise.
    const Piece& piece = pieces_[std::size_t(stub.own_piece)];
    std::vector<Vec2> pts;
    for (Vec2 v : piece.points) pts.push_back(origin + rotated(v, stub.heading));
    if (std::optional<Outcome> o = evaluate(stub, piece, std::move(pts), Spacing::laid_out)) {
      commit(stub, piece, std::move(*o));
      return;
    }
  }
  const int candidates = retry ? 4 * options_.candidates : options_.candidates;
  // While the output is short of the exemplar's dangling ends a gap from a line, one more
  // candidate is drawn among the pieces that end so (they are few: drawn among all, they
  // seldom come up).
  const bool short_of_gaps = !gap_pieces_.empty() && short_of_gap_ends();
  for (int c = 0; c < candidates + int(short_of_gaps); ++c) {
    const Piece& piece =
        pieces_[std::size_t(c == candidates ? gap_pieces_[rng_.below(gap_pieces_.size())]
                                            : rng_.below(pieces_.size()))];
    const double noise = 0.15 * rng_.uniform();
    std::vector<Vec2> pts;
    for (Vec2 v : piece.points) pts.push_back(origin + rotated(v, stub.heading));
    std::optional<Outcome> o = evaluate(stub, piece, std::move(pts));
    if (!o) continue;
    // Turned as little as possible from how it lies in the exemplar: the exemplar's
    // anisotropy (rows of fields, walls along contours) carries over.
    const double turned = std::abs(wrap(stub.heading - (piece.heading + turn_))) / kPi;
    o->cost = outcome_cost(*o) + opened_cost(*o, piece) + kTurnWeight * turned + noise +
              kBearingMatchWeight * bearing_cdf_.step_cost(o->line.back() - o->line.front());
    if (!best || o->cost < best->cost) best = std::move(o), best_piece = &piece;
  }
  if (!best && !retry) {
    failed_.push_back(stub);
    return;
  }
  if (!best) {
    // The node stays short of the junction it was meant to be.
    ++report_.rejected_crossing;
    const std::size_t n = std::size_t(stub.node);
    if (!out_.on_boundary[n] && planned_[n] > 0) {
      have_degree_[std::size_t(std::min(planned_[n], 6))] -= 1.0;
      --planned_[n];
      if (planned_[n] > 0)
        have_degree_[std::size_t(std::min(planned_[n], 6))] += 1.0;
      else
        junction_count_ -= 1.0;
    }
    return;
  }
  commit(stub, *best_piece, std::move(*best));
}

// Shortens a polyline by `by` metres at its end; false when nothing would be left.
bool Grower::cut_back(std::vector<Vec2>& pts, double by) {
  while (pts.size() >= 2) {
    const double last = distance(pts[pts.size() - 2], pts.back());
    if (last > by) {
      pts.back() = pts.back() + (pts[pts.size() - 2] - pts.back()) * (by / last);
      return true;
    }
    by -= last;
    pts.pop_back();
  }
  return false;
}

void Grower::bend_end(std::vector<Vec2>& pts, Vec2 target) {
  const Vec2 d = target - pts.back();
  const double total = polyline_length(pts);
  double s = 0.0;
  for (std::size_t k = 1; k < pts.size(); ++k) {
    s += distance(pts[k - 1], pts[k]);
    pts[k] += d * (total > 0.0 ? s / total : 1.0);
  }
  pts.back() = target;
}

// The angle (radians, 0..pi/2) between the arriving line's last segment and an edge segment.
double Grower::meeting_angle(const std::vector<Vec2>& line, Vec2 a, Vec2 b) {
  const Vec2 u = normalized(line.back() - line[line.size() - 2]), v = normalized(b - a);
  return std::asin(std::min(1.0, std::abs(cross(u, v))));
}

// The pending stub of node n pointing closest to `towards` (radians), within 60°.
int Grower::pending_stub(int n, double towards) const {
  int best = -1;
  double best_diff = kPi / 3;
  for (int id : stubs_of_[std::size_t(n)]) {
    if (cancelled_[std::size_t(id)]) continue;
    const double diff = std::abs(wrap(stubs_[std::size_t(id)].heading - towards));
    if (diff < best_diff) best_diff = diff, best = id;
  }
  return best;
}

// `spacing`: Spacing::laid_out for a laid-out junction's own piece, which lies where the
// exemplar has it beside the laid-out lines.
std::optional<Grower::Outcome> Grower::evaluate(const Stub& stub, const Piece& piece,
                                                std::vector<Vec2> pts, Spacing spacing) {
  Ending ending;
  std::optional<Hit> edge_hit = first_edge_hit(pts);
  std::optional<Hit> wall = first_boundary_hit(pts);
  if (wall &&
      (!edge_hit || wall->k < edge_hit->k || (wall->k == edge_hit->k && wall->t < edge_hit->t))) {
    truncate(pts, *wall);
    ending.kind = Ending::Kind::boundary;
  } else if (edge_hit) {
    truncate(pts, *edge_hit);
    ending.kind = Ending::Kind::edge;
    ending.edge = edge_hit->edge;
    ending.seg = edge_hit->seg;
  }
  if (polyline_length(pts) < min_piece_) return std::nullopt;
  std::vector<Outcome> variants;
  const Vec2 end = pts.back();
  // An end close to a node with an open stub facing it fills that stub (closing a cell).
  std::vector<NodeValue> close;
  nodes_.query(bgi::nearest(to_bg(end), 4), std::back_inserter(close));
  std::sort(close.begin(), close.end(), [&](const NodeValue& a, const NodeValue& b) {
    const double da = distance(vec(a.first), end), db = distance(vec(b.first), end);
    return da != db ? da < db : a.second < b.second;
  });
  if (spacing == Spacing::laid_out && ending.kind == Ending::Kind::free && piece.end_degree == 1) {
    // A dangling end of the exemplar beside the laid-out lines stays one, as the layout's
    // copied ends do (moved to keep the clearance when it must), rather than snapped onto a
    // line the exemplar's end does not reach: drawn lines ending a hair short of another.
    std::vector<Vec2> kept = network_detail::with_free_ends_clear(
        pts, false, true, clearance_, [&](Vec2 p) { return clear_of_lines(p); });
    if (!kept.empty()) variants.push_back({ending, std::move(kept), 1, -1});
  }
  const double reach = ending.kind == Ending::Kind::free ? snap_ : 2.0 * clearance_;
  for (const NodeValue& n : close) {
    if (n.second == stub.node || distance(vec(n.first), end) > reach) continue;
    if (out_.on_boundary[std::size_t(n.second)] || connected(n.second, stub.node)) continue;
    std::vector<Vec2> bent = pts;
    bend_end(bent, vec(n.first));
    const int taken = pending_stub(n.second, leaving(bent, false));
    if (taken < 0) continue;
    variants.push_back({Ending{Ending::Kind::node, n.second, -1, -1}, std::move(bent), 0, taken});
    break;
  }
  if (ending.kind == Ending::Kind::free) {
    std::vector<SegValue> near;
    segments_.query(bgi::nearest(to_bg(end), 1), std::back_inserter(near));
    if (!near.empty() && bg::distance(near[0].first, to_bg(end)) < snap_) {
      const Vec2 a = vec(near[0].first.first), b = vec(near[0].first.second);
      const Vec2 ab = b - a;
      const double t = std::clamp(dot(end - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
      const Vec2 foot = a + ab * t;
      const auto& e = out_.edges[std::size_t(near[0].second)];
      if (t > 0.0 && t < 1.0 && e.from != stub.node && e.to != stub.node) {
        int seg = 0;
        for (std::size_t j = 0; j + 1 < e.points.size(); ++j)
          if (e.points[j] == a && e.points[j + 1] == b) seg = int(j);
        std::vector<Vec2> bent = pts;
        bend_end(bent, foot);
        variants.push_back({Ending{Ending::Kind::edge, -1, near[0].second, seg}, std::move(bent),
                            line_meeting_degree_, -1});
      }
    }
  }
  const int plain_degree = ending.kind == Ending::Kind::free   ? piece.end_degree
                           : ending.kind == Ending::Kind::edge ? line_meeting_degree_
                                                               : 0;
  variants.push_back({ending, pts, plain_degree, -1});
  // A piece that stops a gap short of a line in the exemplar keeps its end free, a gap short
  // of the line it meets or would be snapped onto, while the output has fewer such ends than
  // the exemplar's share of its nodes (a grid's field boundaries with gaps).
  if (piece.ends_at_line && ending.kind != Ending::Kind::boundary && short_of_gap_ends()) {
    if (ending.kind == Ending::Kind::edge) {
      std::vector<Vec2> short_of = pts;
      if (cut_back(short_of, kDanglingGap * clearance_))
        variants.insert(variants.begin(), {Ending{}, std::move(short_of), 1, -1});
    } else {
      std::rotate(variants.begin(), variants.end() - 1, variants.end());
    }
  }
  for (Outcome& o : variants) {
    auto& line = o.line;
    if (polyline_length(line) < min_piece_) continue;
    if (o.how.kind == Ending::Kind::edge) {
      // Not onto an edge beside its own end nodes, nor at a glancing angle (a sliver cell).
      const NetworkEdge& e = out_.edges[std::size_t(o.how.edge)];
      if (distance(line.back(), out_.nodes[std::size_t(e.from)]) < clearance_ ||
          distance(line.back(), out_.nodes[std::size_t(e.to)]) < clearance_)
        continue;
      if (meeting_angle(line, e.points[std::size_t(o.how.seg)],
                        e.points[std::size_t(o.how.seg) + 1]) < kMinMeetingAngle)
        continue;
    }
    const bool joint = o.how.kind == Ending::Kind::node || o.how.kind == Ending::Kind::edge;
    if (o.how.kind == Ending::Kind::boundary) {
      // Pulled a hair inside, so that the end is in the region for every reader.
      const Vec2 back = line[line.size() - 2];
      line.back() =
          line.back() +
          (back - line.back()) *
              std::min(0.5, 1e-9 * median_ / std::max(distance(back, line.back()), 1e-300));
    }
    if (!valid(line, joint, spacing)) continue;
    return std::move(o);
  }
  return std::nullopt;
}

void Grower::commit(const Stub& stub, const Piece& piece, Outcome o) {
  ++report_.placed;
  std::vector<Vec2> pts = std::move(o.line);
  const double arrive = leaving(pts, false) + kPi;
  int end = -1;
  switch (o.how.kind) {
    case Ending::Kind::node:
      end = o.how.node;
      cancelled_[std::size_t(o.stub_taken)] = 1;
      ++report_.snapped;
      break;
    case Ending::Kind::edge:
      end = split_edge(o.how.edge, o.how.seg, pts.back());
      pts.back() = out_.nodes[std::size_t(end)];
      planned_[std::size_t(end)] = line_meeting_degree_;
      ++report_.t_junctions;
      // Where the exemplar's lines cross rather than end on each other, the line goes on
      // through the line it met (an X-junction), when a piece fits beyond it.
      if (line_meeting_degree_ == 4) push_stub(end, arrive);
      break;
    case Ending::Kind::boundary:
      end = add_node(pts.back());
      out_.on_boundary[std::size_t(end)] = 1;
      ++report_.boundary_ends;
      break;
    case Ending::Kind::free:
      end = add_node(pts.back());
      planned_[std::size_t(end)] = piece.end_degree;
      break;
  }
  if (o.degree > 0) {
    have_degree_[std::size_t(std::min(o.degree, 6))] += 1.0;
    junction_count_ += 1.0;
  }
  if (o.how.kind == Ending::Kind::free && o.degree == 1 && piece.ends_at_line) gap_ends_ += 1.0;
  have_bearing_[std::size_t(bearing_bin(pts.back() - pts.front()))] += 1.0;
  have_length_[std::size_t(length_bin(polyline_length(pts)))] += 1.0;
  placed_ += 1.0;
  grown_length_ += polyline_length(pts);
  // The stroke's junctions passed through become nodes with stubs of their own.
  int from = stub.node;
  std::size_t first = 0;
  const double total = polyline_length(pts);
  double along = 0.0;
  std::size_t measured = 0;
  for (std::size_t k = 0; k < piece.sides.size();) {
    const std::size_t at = piece.sides[k].first;
    std::vector<double> turns;
    for (; k < piece.sides.size() && piece.sides[k].first == at; ++k)
      turns.push_back(piece.sides[k].second);
    if (at == 0 || at + 1 >= pts.size()) continue;
    for (; measured < at; ++measured) along += distance(pts[measured], pts[measured + 1]);
    if (along < min_piece_ || total - along < min_piece_) continue;
    // A junction passed through only while the network has fewer junctions per metre than
    // the exemplar (other lines also end on this one: both would double the density).
    if (grown_length_ < length_per_junction_ * (junctions() + 1.0)) continue;
    const int node = add_node(pts[at]);
    NetworkEdge part;
    part.from = from;
    part.to = node;
    part.points.assign(pts.begin() + long(first), pts.begin() + long(at) + 1);
    add_edge(std::move(part));
    planned_[std::size_t(node)] = 2 + int(turns.size());
    have_degree_[std::size_t(std::min(planned_[std::size_t(node)], 6))] += 1.0;
    junction_count_ += 1.0;
    const double arrive_here = heading(pts[at] - pts[at - 1]);
    for (double turn : turns) push_stub(node, wrap(arrive_here + turn));
    from = node;
    first = at;
  }
  NetworkEdge e;
  e.from = from;
  e.to = end;
  e.points.assign(pts.begin() + long(first), pts.end());
  add_edge(std::move(e));
  if (o.how.kind == Ending::Kind::free)
    for (double turn : piece.end_turns) push_stub(end, wrap(arrive + turn));
}

void Grower::push_stub(int node, double heading, int own_piece) {
  const int id = int(stubs_.size());
  stubs_.push_back({node, heading, id, own_piece});
  cancelled_.push_back(0);
  stubs_of_[std::size_t(node)].push_back(id);
  queue_.push_back(stubs_.back());
}

void Grower::retry_failed() {
  std::vector<Stub> failed;
  failed.swap(failed_);
  for (const Stub& stub : failed) {
    if (degree_[std::size_t(stub.node)] >= planned_[std::size_t(stub.node)]) continue;
    grow_stub(stub, true);
    drain();  // what the retried piece opened
    for (const Stub& again : failed_) grow_stub(again, true);
    failed_.clear();
  }
}

void Grower::drain() {
  while (!queue_.empty()) {
    const Stub s = queue_.front();
    queue_.pop_front();
    grow_stub(s);
  }
}

// Seeds on a lattice over the region, in a seeded order, wherever the network has not reached.
void Grower::seed_lattice() {
  const double spacing = median_;
  const BgPoint lo = extent_.min_corner(), hi = extent_.max_corner();
  const int nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / spacing)));
  const int ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / spacing)));
  std::vector<std::int64_t> order(std::size_t(nx) * std::size_t(ny));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::int64_t(i);
  // Centre first (the network grows outward from one seed), the rest shuffled.
  const std::int64_t centre = std::int64_t(ny / 2) * nx + nx / 2;
  std::swap(order[0], order[std::size_t(centre)]);
  for (std::size_t i = order.size() - 1; i > 1; --i) std::swap(order[i], order[1 + rng_.below(i)]);
  for (std::int64_t cell : order) {
    // Cells of the region's extent divided evenly (a region smaller than one spacing still
    // gets its centre).
    const Vec2 p{lo.x() + (double(cell % nx) + 0.5) * (hi.x() - lo.x()) / nx,
                 lo.y() + (double(cell / nx) + 0.5) * (hi.y() - lo.y()) / ny};
    if (!inside_region(p) || forbidden_at(p, true)) continue;
    std::vector<SegValue> near;
    segments_.query(bgi::nearest(to_bg(p), 1), std::back_inserter(near));
    if (!near.empty() && bg::distance(near[0].first, to_bg(p)) < seed_room_) continue;
    if (near_boundary(p) ||
        (layout_copies_ && layout_copies_->empty_near(p, kLayoutEmptyReach * spacing)))
      continue;
    const std::size_t j = std::size_t(rng_.below(junctions_.size()));
    const int node = add_node(p);
    ++report_.seeds;
    planned_[std::size_t(node)] = int(junction_headings_[j].size());
    have_degree_[std::size_t(std::min(planned_[std::size_t(node)], 6))] += 1.0;
    junction_count_ += 1.0;
    for (double h : junction_headings_[j]) push_stub(node, h);
    drain();
  }
}

}  // namespace network_detail

using network_detail::Grower;
using network_detail::kLayoutShare;
using network_detail::kLayoutStrokeFraction;
using network_detail::kStrokeDeflection;

namespace {

// How close a network's style is to the exemplar's: how many of the quality targets it meets
// (docs/networks.md, "Quality": each property's normalized W1 distance within 1.5 × the
// exemplar's own half-to-half distance or 0.05, the dangling ends within 1.5 × the exemplar's
// rate), and, to break ties, the sum of the distances (each capped at 5: an empty sample is not
// infinitely worse) and of the difference of the dangling ends' rates relative to the
// exemplar's (at least 0.5 per km).
struct StyleScore {
  int met = 0;
  double distance = 0.0;
  bool better_than(const StyleScore& o) const {
    return met != o.met ? met > o.met : distance < o.distance;
  }
};

struct ExemplarStyle {
  NetworkStats whole, half[2];
  explicit ExemplarStyle(const Network& exemplar) : whole(network_stats(exemplar)) {
    const auto [a, b] = halves(exemplar);
    half[0] = network_stats(exemplar, a);
    half[1] = network_stats(exemplar, b);
  }
  StyleScore score(const Network& network) const {
    const NetworkStats s = network_stats(network);
    StyleScore score;
    for (int p = 0; p < 6; ++p) {
      const double d = normalized_w1(property(whole, p), property(s, p));
      const double own = normalized_w1(property(half[0], p), property(half[1], p));
      score.met += d <= std::max(1.5 * own, 0.05);
      score.distance += std::min(5.0, d);
    }
    score.met += s.dangling_per_km() <= 1.5 * whole.dangling_per_km() + 1e-9;
    score.distance += std::min(5.0, std::abs(s.dangling_per_km() - whole.dangling_per_km()) /
                                        std::max(0.5, whole.dangling_per_km()));
    return score;
  }
};

}  // namespace

Network grow_network(const Network& exemplar, const std::vector<Polygon>& region,
                     const ForbiddenMask* forbidden, const Network* partial,
                     const NetworkGrowthOptions& options, NetworkGrowthReport* report) {
  using Mode = Grower::Mode;
  const auto make = [&](Mode mode, NetworkGrowthReport& counters) {
    Grower grower(exemplar, region, forbidden, options, counters);
    if (partial) grower.add_partial(*partial);
    return grower.run(mode);
  };
  NetworkGrowthReport local;
  if (options.method != NetworkMethod::automatic || partial)
    return make(options.method == NetworkMethod::quilt    ? Mode::quilt
                : options.method == NetworkMethod::layout ? Mode::layout
                                                          : Mode::grow,
                report ? *report : local);
  // Growth, the quilt and, when the exemplar has long strokes, growth from their layout; the
  // one meeting the most targets on the exemplar's statistics (ties: the closer, then the
  // first).
  std::vector<Mode> modes{Mode::grow, Mode::quilt};
  const std::vector<double> skeleton = network_detail::long_stroke_edges(
      exemplar, kStrokeDeflection, kLayoutStrokeFraction, kLayoutShare);
  if (std::find_if(skeleton.begin(), skeleton.end(), [](double l) { return l > 0.0; }) !=
      skeleton.end())
    modes.push_back(Mode::layout);
  const ExemplarStyle style(exemplar);
  Network best;
  StyleScore best_score;
  NetworkGrowthReport best_report;
  for (std::size_t m = 0; m < modes.size(); ++m) {
    NetworkGrowthReport counters;
    Network candidate = make(modes[m], counters);
    const StyleScore score = style.score(candidate);
    if (m == 0 || score.better_than(best_score))
      best = std::move(candidate), best_score = score, best_report = counters;
  }
  if (report) *report = best_report;
  return best;
}

GridSpec forbidden_mask_grid(const std::vector<Polygon>& region) {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (const Polygon& polygon : region)
    for (Vec2 p : polygon.front()) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  GridSpec grid;
  const double pixel = std::max({1.0, (hi.x - lo.x) / 4096.0, (hi.y - lo.y) / 4096.0});
  grid.width = int(std::ceil((hi.x - lo.x) / pixel)) + 2;
  grid.height = int(std::ceil((hi.y - lo.y) / pixel)) + 2;
  grid.origin_x = lo.x - pixel;
  grid.origin_y = hi.y + pixel;
  grid.pixel_width = grid.pixel_height = pixel;
  return grid;
}

void forbid_nodata_cells(std::optional<ForbiddenMask>& mask, const std::vector<Polygon>& region,
                         const GridSpec& heights_grid,
                         const std::function<Raster<float>(const Window&)>& read_heights) {
  const GridSpec grid = mask ? mask->grid : forbidden_mask_grid(region);
  // The heightfield's cells under the mask (edges shared within 1e-9 of a cell excluded).
  const Vec2 lo = heights_grid.world_to_pixel(grid.pixel_to_world({0.0, 0.0}));
  const Vec2 hi =
      heights_grid.world_to_pixel(grid.pixel_to_world({double(grid.width), double(grid.height)}));
  Window window;
  window.col0 = std::max(0, int(std::floor(lo.x + 1e-9)));
  window.row0 = std::max(0, int(std::floor(lo.y + 1e-9)));
  window.width = std::min(heights_grid.width, int(std::ceil(hi.x - 1e-9))) - window.col0;
  window.height = std::min(heights_grid.height, int(std::ceil(hi.y - 1e-9))) - window.row0;
  if (window.width <= 0 || window.height <= 0) return;
  const Raster<float> heights = read_heights(window);
  Raster<std::uint8_t> nodata(grid.width, grid.height);
  bool any = false;
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const Vec2 a = heights_grid.world_to_pixel(grid.pixel_to_world({double(col), double(row)}));
      const Vec2 b =
          heights_grid.world_to_pixel(grid.pixel_to_world({double(col + 1), double(row + 1)}));
      const int c0 = std::max(window.col0, int(std::floor(a.x + 1e-9)));
      const int c1 = std::min(window.col0 + window.width, int(std::ceil(b.x - 1e-9))) - 1;
      const int r0 = std::max(window.row0, int(std::floor(a.y + 1e-9)));
      const int r1 = std::min(window.row0 + window.height, int(std::ceil(b.y - 1e-9))) - 1;
      bool hole = false;
      for (int r = r0; r <= r1 && !hole; ++r)
        for (int c = c0; c <= c1 && !hole; ++c)
          hole = std::isnan(heights.at(c - window.col0, r - window.row0));
      if (hole) nodata.at(col, row) = 1, any = true;
    }
  if (!any) return;
  if (!mask) mask = ForbiddenMask{grid, Raster<std::uint8_t>(grid.width, grid.height)};
  for (std::size_t i = 0; i < nodata.pixels.size(); ++i)
    if (nodata.pixels[i]) mask->cells.pixels[i] = 1;
}

}  // namespace tw
