// Grower: what it learns from the exemplar; the region and its forbidden cells.

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

// A lattice seed goes where no line is nearer than this quantile of the exemplar's own distances
// from its extent to its lines (at least 0.75 median edge length).
constexpr double kSeedRoomQuantile = 0.9;

// An exemplar whose lines come within the clearance of this share of its extent's perimeter
// has a drawn frame: its border is that frame, not its outermost cells' sides (keep_whole_cells).
constexpr double kFrameShare = 0.9;

}  // namespace

void Grower::learn(const Network& ex) {
  const std::vector<int> degree = ex.degrees();
  std::vector<std::vector<std::pair<double, int>>> leaving_at(ex.nodes.size());
  for (std::size_t i = 0; i < ex.edges.size(); ++i) {
    const NetworkEdge& e = ex.edges[i];
    leaving_at[std::size_t(e.from)].push_back({leaving(e.points, true), int(i)});
    leaving_at[std::size_t(e.to)].push_back({leaving(e.points, false), int(i)});
  }
  const auto boundary = [&](int n) {
    return !ex.on_boundary.empty() && ex.on_boundary[std::size_t(n)];
  };
  std::vector<double> lengths;
  for (const NetworkEdge& e : ex.edges)
    if (!boundary(e.from) && !boundary(e.to)) lengths.push_back(polyline_length(e.points));
  if (lengths.empty())
    for (const NetworkEdge& e : ex.edges) lengths.push_back(polyline_length(e.points));
  if (lengths.empty()) fail("exemplar: no edges to learn from");
  std::sort(lengths.begin(), lengths.end());
  median_ = lengths[lengths.size() / 2];
  if (!(median_ > 0.0)) fail("exemplar: its edges have no length");
  for (int b = 1; b < 8; ++b) length_edges_.push_back(lengths[lengths.size() * std::size_t(b) / 8]);
  clearance_ = options_.clearance > 0.0 ? options_.clearance : 0.06 * median_;
  snap_ = options_.snap > 0.0 ? options_.snap : std::max(0.35 * median_, 2.0 * clearance_);
  // No edge shorter than most of the exemplar's (its 10th percentile): truncated pieces that
  // would make slivers are refused.
  min_piece_ = std::max({2.5 * clearance_, 0.12 * median_, 0.8 * lengths[lengths.size() / 10]});

  // The turn of the whole exemplar to the lead: its main bearing (the length-weighted mode of
  // its chords' bearings in 10° bins, then their length-weighted mean within that bin).
  if (options_.lead_bearing) {
    std::array<double, 18> weight{}, sum{};
    for (const NetworkEdge& e : ex.edges) {
      const Vec2 c = e.points.back() - e.points.front();
      const double b = std::fmod(std::atan2(c.x, c.y) * 180.0 / kPi + 360.0, 180.0);
      const std::size_t bin = std::size_t(std::min(17, int(b / 10.0)));
      weight[bin] += polyline_length(e.points);
      sum[bin] += b * polyline_length(e.points);
    }
    const std::size_t main =
        std::size_t(std::max_element(weight.begin(), weight.end()) - weight.begin());
    const double main_bearing = weight[main] > 0.0 ? sum[main] / weight[main] : 0.0;
    turn_ = -(*options_.lead_bearing - main_bearing) * kPi / 180.0;
  }
  piece_of_.assign(2 * ex.edges.size(), -1);
  const std::vector<char> at_line = dangling_at_line(ex, degree, clearance_);
  for (std::size_t i = 0; i < ex.edges.size(); ++i) {
    const NetworkEdge& e = ex.edges[i];
    for (int dir = 0; dir < 2; ++dir) {
      const int start = dir == 0 ? e.from : e.to, end = dir == 0 ? e.to : e.from;
      if (boundary(end) || boundary(start)) continue;
      Piece p;
      // The stroke from this edge: across junctions where an edge goes on nearly straight.
      std::vector<Vec2> pts = e.points;
      if (dir == 1) std::reverse(pts.begin(), pts.end());
      int at = end, current = int(i);
      std::vector<int> used{int(i)}, visited{start, end};
      while (options_.strokes && int(used.size()) < kStrokeEdges && !boundary(at) &&
             degree[std::size_t(at)] >= 3) {
        const double arrive = leaving(pts, false) + kPi;
        int next = -1;
        double best = kStrokeDeflection;
        for (const auto& [h, edge] : leaving_at[std::size_t(at)]) {
          if (edge == current || std::find(used.begin(), used.end(), edge) != used.end()) continue;
          const double deflection = std::abs(wrap(h - arrive));
          if (deflection < best) best = deflection, next = edge;
        }
        if (next < 0) break;
        const NetworkEdge& n = ex.edges[std::size_t(next)];
        const int far = n.from == at ? n.to : n.from;
        // A stroke never comes back to a node it passed (it would touch itself there).
        if (std::find(visited.begin(), visited.end(), far) != visited.end()) break;
        visited.push_back(far);
        for (const auto& [h, edge] : leaving_at[std::size_t(at)])
          if (edge != current && edge != next)
            p.sides.push_back({pts.size() - 1, wrap(h - arrive)});
        std::vector<Vec2> more = n.points;
        if (n.from != at) std::reverse(more.begin(), more.end());
        pts.insert(pts.end(), more.begin() + 1, more.end());
        used.push_back(next);
        current = next;
        at = far;
      }
      const int stroke_end = at;
      const double h0 = leaving(pts, true);
      p.heading = h0;
      const Vec2 origin = pts.front();
      for (Vec2 v : pts) p.points.push_back(rotated(v - origin, -h0));
      p.length = polyline_length(p.points);
      if (p.length <= 0.0 || boundary(stroke_end)) continue;
      const double arrive = leaving(pts, false) + kPi;  // heading of travel at the end
      p.arrival = wrap(arrive - h0);
      p.end_degree = degree[std::size_t(stroke_end)];
      p.ends_at_line = at_line[std::size_t(stroke_end)] != 0;
      for (const auto& [h, edge] : leaving_at[std::size_t(stroke_end)])
        if (edge != current ||
            ex.edges[std::size_t(current)].from == ex.edges[std::size_t(current)].to)
          p.end_turns.push_back(wrap(h - arrive));
      if (ex.edges[std::size_t(current)].from == ex.edges[std::size_t(current)].to &&
          !p.end_turns.empty())
        p.end_turns.pop_back();
      p.length_bin = int(std::upper_bound(length_edges_.begin(), length_edges_.end(), p.length) -
                         length_edges_.begin());
      if (p.ends_at_line) gap_pieces_.push_back(int(pieces_.size()));
      piece_of_[2 * i + std::size_t(dir)] = int(pieces_.size());
      pieces_.push_back(std::move(p));
    }
  }
  if (pieces_.empty()) fail("exemplar: every edge is cut by its region (no whole piece)");
  // Target histograms.
  for (std::size_t n = 0; n < ex.nodes.size(); ++n) {
    if (boundary(int(n)) || degree[n] == 0) continue;
    const int d = std::min(degree[n], 6);
    target_degree_[std::size_t(d)] += 1.0;
    if (degree[n] >= 3) junctions_.push_back(int(n));
    if (at_line[n]) gap_share_ += 1.0;
    ++exemplar_nodes_;
  }
  if (junctions_.empty())
    for (std::size_t n = 0; n < ex.nodes.size(); ++n)
      if (degree[n] >= 2) junctions_.push_back(int(n));
  if (junctions_.empty()) fail("exemplar: no junction (every line ends alone)");
  length_per_junction_ = ex.total_length() / double(std::max<std::size_t>(1, junctions_.size()));
  for (double& v : target_degree_) v /= std::max(1, exemplar_nodes_);
  gap_share_ /= std::max(1, exemplar_nodes_);
  double total = 0.0;
  for (const NetworkEdge& e : ex.edges) {
    const Vec2 c = rotated(e.points.back() - e.points.front(), turn_);
    target_bearing_[std::size_t(bearing_bin(c))] += 1.0, total += 1.0;
    bearing_cdf_.add_target(c);
    if (!(c == Vec2{}) && polyline_length(e.points) > 0.0)
      exemplar_bearings_.push_back(chord_bearing(c));
  }
  for (double& v : target_bearing_) v /= std::max(1.0, total);
  {
    std::array<double, 12> sorted = target_bearing_;
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    few_orientations_ = sorted[0] + sorted[1] >= kFewOrientations;
  }
  for (const Piece& p : pieces_) target_length_[std::size_t(p.length_bin)] += 1.0;
  for (double& v : target_length_) v /= double(pieces_.size());
  dangling_target_ = 0.0;
  {
    int dangling = 0;
    double length = 0.0;
    for (std::size_t n = 0; n < ex.nodes.size(); ++n)
      if (degree[n] == 1 && !boundary(int(n))) ++dangling;
    for (const NetworkEdge& e : ex.edges) length += polyline_length(e.points);
    dangling_target_ = dangling / std::max(length, 1e-9);
    // Where lines end free (a third of the nodes or more: a forest of trees), the gaps between
    // them are the exemplar's style: a lattice seed needs as much room as most of its gaps.
    // And where such trees cross rather than end on each other, a branch meeting a line goes
    // on through it.
    seed_room_ = 0.75 * median_;
    forest_ = 3 * dangling >= exemplar_nodes_;
    if (forest_) {
      const NetworkStats own = network_stats(ex);
      exemplar_degrees_ = own.degree;
      exemplar_curvature_ = own.curvature;
      const auto [one, other] = halves(ex);
      const NetworkStats half = network_stats(ex, one), other_half = network_stats(ex, other);
      own_degree_apart_ = normalized_w1(half.degree, other_half.degree);
      own_curvature_apart_ = normalized_w1(half.curvature, other_half.curvature);
      seed_room_ = std::max(seed_room_, empty_space_quantile(ex, 0.5 * median_, kSeedRoomQuantile));
      if (lines_cross_more_than_they_end_on_lines(ex, kStrokeDeflection)) line_meeting_degree_ = 4;
    }
    whole_cells_ =
        dangling == 0 &&
        std::none_of(ex.on_boundary.begin(), ex.on_boundary.end(), [](char b) { return b != 0; }) &&
        !has_drawn_frame(ex, clearance_, kFrameShare);
  }
  {
    std::size_t straight = 0;
    for (const NetworkEdge& e : ex.edges) straight += polyline_turning(e.points) < kStraightTurning;
    straight_share_ = double(straight) / double(ex.edges.size());
    // Its few bent edges (a frame's corners, a border's sides): how sharply they turn; and how
    // narrowly its straight lines meet.
    if (straight_share_ >= kStraightShare) {
      for (const NetworkEdge& e : ex.edges)
        if (const double turning = polyline_turning(e.points); turning >= kStraightTurning) {
          const double c = turning / polyline_length(e.points);
          bend_curvature_mean_ += c / double(ex.edges.size() - straight);
          bend_curvature_max_ = std::max(bend_curvature_max_, c);
        }
      const std::vector<double> angles = network_stats(ex).junction_angle;
      if (!angles.empty())
        narrowest_junction_ = *std::min_element(angles.begin(), angles.end()) * kPi / 180.0;
    }
    // Closed cells with straight sides (fields split by straight hedges): a larger cell of the
    // output is one no line split (split_large_cells, where the exemplar's lines end on each
    // other in Ts: a chord makes a T), a smaller one a sliver between lines that a line apart
    // would have left out (merge_small_cells).
    if (dangling_target_ == 0.0 && straight_share_ >= kStraightShare) {
      const JunctionsGoingOn count = junctions_going_on(ex, kStrokeDeflection);
      cells_end_in_ts_ = double(count.t_junctions) >= kTJunctionShare * double(count.three_way);
      const std::vector<double> areas = network_stats(ex).face_area;
      if (!areas.empty()) {
        max_cell_area_ = *std::max_element(areas.begin(), areas.end());
        min_cell_area_ = *std::min_element(areas.begin(), areas.end());
      }
    }
  }
  for (int j : junctions_) {
    std::vector<double> h;
    for (const auto& [a, edge] : leaving_at[std::size_t(j)]) h.push_back(a + turn_);
    junction_headings_.push_back(std::move(h));
  }
}

// Per exemplar node: whether it is a dangling end within `reach` of another of its lines (a
// gap short of that line, or a line touching it that the noding did not split).
std::vector<char> Grower::dangling_at_line(const Network& ex, const std::vector<int>& degree,
                                           double reach) {
  std::vector<int> own(ex.nodes.size(), -1);
  std::vector<SegValue> segments;
  for (std::size_t i = 0; i < ex.edges.size(); ++i) {
    const NetworkEdge& e = ex.edges[i];
    own[std::size_t(e.from)] = own[std::size_t(e.to)] = int(i);
    for (std::size_t k = 0; k + 1 < e.points.size(); ++k)
      segments.push_back({BgSegment(to_bg(e.points[k]), to_bg(e.points[k + 1])), int(i)});
  }
  const bgi::rtree<SegValue, bgi::quadratic<16>> index(segments);
  std::vector<char> at_line(ex.nodes.size(), 0);
  for (std::size_t n = 0; n < ex.nodes.size(); ++n) {
    if (degree[n] != 1) continue;
    const BgPoint p = to_bg(ex.nodes[n]);
    std::vector<SegValue> nearest;
    index.query(
        bgi::nearest(p, 1) && bgi::satisfies([&](const SegValue& v) { return v.second != own[n]; }),
        std::back_inserter(nearest));
    at_line[n] = !nearest.empty() && bg::distance(nearest[0].first, p) <= reach;
  }
  return at_line;
}

void Grower::set_region(const std::vector<Polygon>& region) {
  double area = 0.0;
  for (const Polygon& polygon : region) {
    BgPolygon p;
    for (std::size_t r = 0; r < polygon.size(); ++r) {
      auto& ring = r == 0 ? p.outer() : (p.inners().emplace_back(), p.inners().back());
      for (Vec2 v : polygon[r]) ring.push_back(to_bg(v));
      if (!polygon[r].empty()) ring.push_back(to_bg(polygon[r].front()));
      for (std::size_t k = 0; k < polygon[r].size(); ++k) {
        const Vec2 a = polygon[r][k], b = polygon[r][(k + 1) % polygon[r].size()];
        if (!(a == b)) boundary_.insert(BgSegment(to_bg(a), to_bg(b)));
      }
    }
    bg::correct(p);
    area += bg::area(p);
    region_.push_back(std::move(p));
  }
  if (!(area > 0.0)) fail("a degenerate (zero-area) region");
  if (area / (median_ * median_) > kMaxNetworkCells)
    fail(
        "{:.0f} km² is too large for an exemplar whose edges are {:.0f} m long (at "
        "most {:.0f} km²: about 10⁷ junctions)",
        area / 1e6, median_, kMaxNetworkCells * median_ * median_ / 1e6);
  bg::envelope(region_, extent_);
  out_.on_boundary.clear();
}

bool Grower::near_boundary(Vec2 p) const {
  std::vector<BgSegment> near;
  const double eps = 1e-6 * std::max(1.0, median_);
  boundary_.query(bgi::intersects(BgBox({p.x - eps, p.y - eps}, {p.x + eps, p.y + eps})),
                  std::back_inserter(near));
  return !near.empty();
}

void Grower::dilate_forbidden() {
  const ForbiddenMask& f = *forbidden_;
  const int r = int(std::ceil(clearance_ / std::min(f.grid.pixel_width, f.grid.pixel_height)));
  Raster<std::uint8_t> rows(f.cells.width, f.cells.height, 0);
  for (int y = 0; y < f.cells.height; ++y)
    for (int x = 0; x < f.cells.width; ++x)
      if (f.cells.at(x, y))
        for (int dx = std::max(0, x - r); dx <= std::min(f.cells.width - 1, x + r); ++dx)
          rows.at(dx, y) = 1;
  dilated_ = Raster<std::uint8_t>(f.cells.width, f.cells.height, 0);
  for (int y = 0; y < f.cells.height; ++y)
    for (int x = 0; x < f.cells.width; ++x)
      if (rows.at(x, y))
        for (int dy = std::max(0, y - r); dy <= std::min(f.cells.height - 1, y + r); ++dy)
          dilated_.at(x, dy) = 1;
}

bool Grower::enters_forbidden(const std::vector<Vec2>& pts) const {
  if (!forbidden_) return false;
  const double step = 0.5 * std::min(forbidden_->grid.pixel_width, forbidden_->grid.pixel_height);
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const double len = distance(pts[k], pts[k + 1]);
    const int n = std::max(1, int(std::ceil(len / step)));
    for (int i = 0; i <= n; ++i)
      if (forbidden_at(lerp(pts[k], pts[k + 1], double(i) / n), true)) return true;
  }
  return false;
}

}  // namespace tw::network_detail
