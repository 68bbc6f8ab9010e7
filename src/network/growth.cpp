#include "network/growth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <optional>

#include "core/boost_geometry.hpp"
#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "core/split_mix.hpp"
#include "network/detail/bearing_cdf.hpp"
#include "network/detail/border.hpp"
#include "network/detail/forest.hpp"
#include "network/detail/layout_copies.hpp"
#include "network/detail/quilt.hpp"
#include "network/detail/skeleton.hpp"
#include "network/stats.hpp"

namespace tw {

namespace {

using namespace geometry;
using SegValue = std::pair<BgSegment, int>;  // a segment of an edge (its index)
using NodeValue = std::pair<BgPoint, int>;
using BgMultiPolygon = bg::model::multi_polygon<BgPolygon>;
constexpr double kPi = std::numbers::pi;

Vec2 vec(const BgPoint& p) {
  return {p.x(), p.y()};
}
Vec2 rotate(Vec2 v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
double heading(Vec2 v) {
  return std::atan2(v.y, v.x);
}
double wrap(double a) {  // (-pi, pi]
  a = std::fmod(a + kPi, 2 * kPi);
  if (a <= 0) a += 2 * kPi;
  return a - kPi;
}
// Bearing bin (15°, 0..11) of a chord, from north, modulo 180°.
int bearing_bin(Vec2 chord) {
  double b = std::atan2(chord.x, chord.y) * 180.0 / kPi;
  b = std::fmod(b + 360.0, 180.0);
  return std::min(11, int(b / 15.0));
}

// First distinct-point heading leaving an end of a polyline.
double leaving(const std::vector<Vec2>& pts, bool from_start) {
  return network_detail::leaving_heading(pts, from_start);
}

// A whole exemplar edge, walked from one end: start at the origin heading +x.
struct Piece {
  std::vector<Vec2> points;
  double length = 0.0;
  double arrival = 0.0;           // heading at the end, relative to the start heading
  int end_degree = 1;             // the exemplar junction at its end
  std::vector<double> end_turns;  // its other edges' headings relative to the arrival
  int length_bin = 0;
  // Junctions passed through (a stroke goes on across a junction where an edge continues
  // nearly straight): the vertex and the other edges' headings relative to the arrival there.
  std::vector<std::pair<std::size_t, double>> sides;
  double heading = 0.0;  // its start heading in the exemplar (radians)
  // Its end is a dangling end within the snap radius of another exemplar line: a gap short of
  // that line (a field boundary stopping at a track), not a line ending alone.
  bool ends_at_line = false;
};

// A stroke continues across a junction onto the edge that deflects least, below this (radians).
constexpr double kStrokeDeflection = 0.12;
constexpr int kStrokeEdges = 8;
// The weight of a piece's turn from its exemplar heading (0..1) in a candidate's cost.
constexpr double kTurnWeight = 0.6;
// A lattice seed goes where no line is nearer than this quantile of the exemplar's own distances
// from its extent to its lines (at least 0.75 median edge length).
constexpr double kSeedRoomQuantile = 0.9;

struct Stub {
  int node = 0;
  double heading = 0.0;
  int id = 0;
  int own_piece = -1;  // a laid-out junction's stub: the piece leaving it in the exemplar
};

// How near other lines a candidate may come (Grower::valid). `grown`: the clearance from every
// line but within the clearance of its joints, both ways, and from its own other segments.
// `copied`: a copy of an exemplar line (the quilt's, the layout's), whose ends may lie near its
// own segments and whose part near a joint may pass another line's corner beyond the joint, as
// in the exemplar. `laid_out`: a copy laid out where the exemplar has it around its joints (the
// layout's lines, a laid-out junction's own piece): the lines meeting it at a joint are exempt
// within the joint's clearance too.
enum class Spacing { grown, copied, laid_out };

// Below this angle (radians) a line does not end on an edge: the cell would be a sliver.
constexpr double kMinMeetingAngle = 0.35;
// The layout copies strokes at least this part of the exemplar's longer side long, when they
// hold at least this share of its length.
constexpr double kLayoutStrokeFraction = 0.4;
constexpr double kLayoutShare = 0.25;
// No lattice seed where the layout's copies have no line within this many median edges.
constexpr double kLayoutEmptyReach = 0.75;
// A node of degree 2 turning more than this (radians) is a corner (close_corners).
constexpr double kCornerTurn = 0.5;
// How far (median edge lengths) a corner's edge is continued to make it a T-junction (3 and 6
// met fewer targets over three seeds: long links break cells).
constexpr double kCornerReach = 1.5;
// How far (median edge lengths) straighten_edges continues a corner's leg that neither its
// chord nor its removal could undo: across the open cell beside it.
constexpr double kChainCornerReach = 4.0;
// The gap, in clearances, that a piece ending alone in the exemplar keeps from the line it
// meets when it is kept dangling (three: a clear gap, not a near miss).
constexpr double kDanglingGap = 3.0;
// The weight of the bearings of the stubs a free end opens in a candidate's cost (opened_cost),
// and the share of the exemplar's edges in its two main 15° bearing bins from which it counts
// (a grid's tracks and field boundaries: nearly all).
constexpr double kOpenedWeight = 3.0;
constexpr double kFewOrientations = 0.75;
// The weight of a candidate's pull on the output's bearing distribution towards the exemplar's
// (BearingCdf::step_cost, about -1..1): it picks among candidates of near-equal cost. 0.3 met the
// most targets (seeds 1-6 of 0, 0.15, 0.3, 0.5, 0.7, 1 and 3; 0.3, 0.4, 0.5 also seeds 7-9);
// from 1 up the grid's curvature and the stream trees' cell areas suffer.
constexpr double kBearingMatchWeight = 0.3;

// An edge turning less than this in all (radians) is straight; an exemplar whose edges are at
// least kStraightShare straight gets straight output edges (Grower::straighten_edges).
constexpr double kStraightTurning = 0.01;
constexpr double kStraightShare = 0.9;
// How far (radians) a straightened edge may leave its junctions off its old heading there.
constexpr double kStraightenDeflection = 1.0;
// A step of an output line shorter than this part of the clearance is a hair (a snapped end's
// last step), left out where the exemplar's lines are straight (Grower::straighten_edges).
constexpr double kShortStep = 0.3;

// An exemplar whose lines come within the clearance of this share of its extent's perimeter
// has a drawn frame: its border is that frame, not its outermost cells' sides (keep_whole_cells).
constexpr double kFrameShare = 0.9;
// A quilt's seam end left alone is linked onto a line within this many median edge lengths.
constexpr double kSeamReach = 1.5;

// Where a candidate ends.
struct Ending {
  enum class Kind { free, node, edge, boundary } kind = Kind::free;
  int node = -1;            // Kind::node
  int edge = -1, seg = -1;  // Kind::edge: the segment hit
};

struct Hit {
  std::size_t k = 0;  // segment of the candidate
  double t = 2.0;     // along it
  Vec2 point;
  int edge = -1, seg = -1;
};

// Intersection parameters of segments pq and ab (proper or touching), or false when parallel.
bool segment_hit(Vec2 p, Vec2 q, Vec2 a, Vec2 b, double& t, double& u) {
  const Vec2 r = q - p, s = b - a;
  const double denom = cross(r, s);
  if (std::abs(denom) <= 1e-12 * (dot(r, r) + dot(s, s))) return false;
  t = cross(a - p, s) / denom;
  u = cross(a - p, r) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

class Grower {
 public:
  Grower(const Network& exemplar, const std::vector<Polygon>& region,
         const ForbiddenMask* forbidden, const NetworkGrowthOptions& options,
         NetworkGrowthReport& report)
      : exemplar_(exemplar),
        forbidden_(forbidden),
        options_(options),
        report_(report),
        rng_(options.seed) {
    learn(exemplar);
    set_region(region);
    if (forbidden_) dilate_forbidden();
  }

  void add_partial(const Network& partial) {
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

  enum class Mode { grow, quilt, layout };
  Network run(Mode mode) {
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
    return finish();
  }

 private:
  // ---- the exemplar --------------------------------------------------------------------------
  void learn(const Network& ex) {
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
    for (int b = 1; b < 8; ++b)
      length_edges_.push_back(lengths[lengths.size() * std::size_t(b) / 8]);
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
            if (edge == current || std::find(used.begin(), used.end(), edge) != used.end())
              continue;
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
        for (Vec2 v : pts) p.points.push_back(rotate(v - origin, -h0));
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
      const Vec2 c = rotate(e.points.back() - e.points.front(), turn_);
      target_bearing_[std::size_t(bearing_bin(c))] += 1.0, total += 1.0;
      bearing_cdf_.add_target(c);
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
      if (3 * dangling >= exemplar_nodes_) {
        seed_room_ = std::max(
            seed_room_, network_detail::empty_space_quantile(ex, 0.5 * median_, kSeedRoomQuantile));
        if (network_detail::lines_cross_more_than_they_end_on_lines(ex, kStrokeDeflection))
          line_meeting_degree_ = 4;
      }
      whole_cells_ = dangling == 0 &&
                     std::none_of(ex.on_boundary.begin(), ex.on_boundary.end(),
                                  [](char b) { return b != 0; }) &&
                     !network_detail::has_drawn_frame(ex, clearance_, kFrameShare);
    }
    {
      std::size_t straight = 0;
      for (const NetworkEdge& e : ex.edges)
        straight += polyline_turning(e.points) < kStraightTurning;
      straight_share_ = double(straight) / double(ex.edges.size());
    }
    for (int j : junctions_) {
      std::vector<double> h;
      for (const auto& [a, edge] : leaving_at[std::size_t(j)]) h.push_back(a + turn_);
      junction_headings_.push_back(std::move(h));
    }
  }

  // Per exemplar node: whether it is a dangling end within `reach` of another of its lines (a
  // gap short of that line, or a line touching it that the noding did not split).
  static std::vector<char> dangling_at_line(const Network& ex, const std::vector<int>& degree,
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
      index.query(bgi::nearest(p, 1) &&
                      bgi::satisfies([&](const SegValue& v) { return v.second != own[n]; }),
                  std::back_inserter(nearest));
      at_line[n] = !nearest.empty() && bg::distance(nearest[0].first, p) <= reach;
    }
    return at_line;
  }

  // ---- the region ----------------------------------------------------------------------------
  void set_region(const std::vector<Polygon>& region) {
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

  bool inside_region(Vec2 p) const { return bg::covered_by(to_bg(p), region_); }
  bool near_boundary(Vec2 p) const {
    std::vector<BgSegment> near;
    const double eps = 1e-6 * std::max(1.0, median_);
    boundary_.query(bgi::intersects(BgBox({p.x - eps, p.y - eps}, {p.x + eps, p.y + eps})),
                    std::back_inserter(near));
    return !near.empty();
  }

  void dilate_forbidden() {
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
  bool forbidden_at(Vec2 p, bool dilated) const {
    if (!forbidden_) return false;
    const Vec2 px = forbidden_->grid.world_to_pixel(p);
    const int c = int(std::floor(px.x)), r = int(std::floor(px.y));
    const Raster<std::uint8_t>& m = dilated ? dilated_ : forbidden_->cells;
    return m.inside(c, r) && m.at(c, r) != 0;
  }
  bool enters_forbidden(const std::vector<Vec2>& pts) const {
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

  // ---- the network so far ----------------------------------------------------------------------
  int add_node(Vec2 p) {
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
  void index_edge(int id, bool insert) {
    const auto& pts = out_.edges[std::size_t(id)].points;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const SegValue v{BgSegment(to_bg(pts[k]), to_bg(pts[k + 1])), id};
      if (insert)
        segments_.insert(v);
      else
        segments_.remove(v);
    }
  }
  int add_edge(NetworkEdge e) {
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
  void count_edge_bearing(const std::vector<Vec2>& pts, double count) {
    if (pts.size() < 2 || pts.back() == pts.front()) return;
    edge_bearing_[std::size_t(bearing_bin(pts.back() - pts.front()))] += count;
    edge_count_ += count;
    bearing_cdf_.add_output(pts.back() - pts.front(), count);
  }
  // Splits edge `id` at `p` on its segment `seg`: the new node.
  int split_edge(int id, int seg, Vec2 p) {
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
    return node;
  }

  // The first place where `pts` meets the network, past its start.
  std::optional<Hit> first_edge_hit(const std::vector<Vec2>& pts) const {
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
  std::optional<Hit> first_boundary_hit(const std::vector<Vec2>& pts) const {
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
  bool valid(const std::vector<Vec2>& pts, bool end_joint, Spacing spacing = Spacing::grown,
             double joint_slack = 0.0) {
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
      const BgBox box(
          {std::min(a.x, b.x) - clearance_ - eps, std::min(a.y, b.y) - clearance_ - eps},
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
            return distance(x, joint) <= joint_slack &&
                   (distance(vec(v.first.first), joint) <= eps ||
                    distance(vec(v.first.second), joint) <= eps);
          };
          const bool at_start = k == 0 && meets(start);
          const bool at_end = end_joint && k + 2 == pts.size() && meets(end);
          if (!at_start && !at_end) return false;
          continue;
        }
        // Segments meeting at a joint (its edges, the edge a T-junction splits) are exempt.
        const Vec2 ea = vec(v.first.first), eb = vec(v.first.second);
        bool at_joint = false;
        for (Vec2 j : joints) at_joint = at_joint || distance_to_segment(j, ea, eb) <= eps;
        if (at_joint) continue;
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
      const BgBox box(
          {std::min(a.x, b.x) - clearance_ - eps, std::min(a.y, b.y) - clearance_ - eps},
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
  bool edge_meets(int id, const std::vector<Vec2>& joints) const {
    const double eps = 1e-7 * median_;
    const std::vector<Vec2>& pts = out_.edges[std::size_t(id)].points;
    for (Vec2 j : joints)
      for (std::size_t k = 0; k + 1 < pts.size(); ++k)
        if (distance_to_segment(j, pts[k], pts[k + 1]) <= eps) return true;
    return false;
  }

  // ---- layout (docs/networks.md, "Layout") ---------------------------------------------------
  // The exemplar's long strokes (the tracks of a grid, terrace walls, rings and spokes) copied
  // rigidly as one piece, repeated at the exemplar's extent to cover the region (a seeded shift
  // of at most half a median edge), committed under the same rules as quilted lines; each of
  // their junctions then gets stubs along the exemplar's other edges there, from which growth
  // fills the cells. A copied dangling end too near a line is moved to keep the clearance, and
  // the copies' empty parts get no lattice seed (layout_copies.hpp). False when the exemplar has
  // no such strokes.
  bool lay_out_long_strokes() {
    const std::vector<double> skeleton = network_detail::long_stroke_edges(
        exemplar_, kStrokeDeflection, kLayoutStrokeFraction, kLayoutShare);
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
    Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (Vec2 p : exemplar_.nodes) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
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
    network_detail::LayoutFrame frame{origin, centre, size, lo, hi, turn_, ni, nj};
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
            kept = network_detail::with_free_ends_clear(
                std::move(kept), free_end(edge.from, kept.front()), free_end(edge.to, kept.back()),
                clearance_, [&](Vec2 p) { return clear_of_lines(p); });
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

  // Whether a new node at p would keep the clearance from every line.
  bool clear_of_lines(Vec2 p) const {
    std::vector<SegValue> near;
    segments_.query(bgi::nearest(to_bg(p), 1), std::back_inserter(near));
    return near.empty() || bg::distance(near[0].first, to_bg(p)) >= clearance_;
  }

  // A placed line counted in the histograms growth steers by.
  void count_line(const std::vector<Vec2>& pts) {
    have_bearing_[std::size_t(bearing_bin(pts.back() - pts.front()))] += 1.0;
    have_length_[std::size_t(length_bin(polyline_length(pts)))] += 1.0;
    placed_ += 1.0;
    grown_length_ += polyline_length(pts);
  }

  // ---- quilting (docs/networks.md, "Quilting") -----------------------------------------------
  // The quilt's lines are committed one by one under the same rules as grown pieces (no
  // crossing but at shared nodes, clearance, region, forbidden cells): a line that breaks one
  // is left out. Seam ends that found no partner are linked straight onto the line ahead, or
  // trimmed back to the last junction.
  void quilt() {
    network_detail::QuiltSettings settings;
    settings.lo = vec(extent_.min_corner());
    settings.hi = vec(extent_.max_corner());
    settings.stitch = 0.6 * snap_;
    settings.clearance = clearance_;
    settings.turn = turn_;
    settings.candidates = 32;
    settings.continuation = kSeamReach * median_;
    std::vector<network_detail::QuiltLine> lines =
        network_detail::quilt_lines(exemplar_, settings, rng_);
    std::vector<std::pair<Vec2, std::vector<Vec2>>> seam_ends;  // and their continuations
    for (network_detail::QuiltLine& line : lines) {
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

  // The parts of a line inside the region; an end cut by the region's boundary is pulled a
  // hair inside (as a grown piece's is).
  std::vector<std::vector<Vec2>> inside_parts(std::vector<Vec2> pts) const {
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
  bool place_line(std::vector<Vec2> pts, double joint_slack = 0.0,
                  Spacing spacing = Spacing::copied) {
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

  // A dangling end removed with its edge, and the chain behind it up to the last junction (at
  // most `at_most` metres of line); the node where it stopped.
  int trim_from(int n, double at_most) {
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

  // ---- growth ----------------------------------------------------------------------------------
  // How far a histogram would move from its target when `bin` gains one (> 0: over-represented).
  template <std::size_t N>
  static double excess(const std::array<double, N>& have, double total,
                       const std::array<double, N>& want, std::size_t bin) {
    return (have[bin] + 1.0) / (total + 1.0) - want[bin];
  }
  int length_bin(double length) const {
    return int(std::upper_bound(length_edges_.begin(), length_edges_.end(), length) -
               length_edges_.begin());
  }

  // A candidate's outcome, evaluated before anything is committed.
  struct Outcome {
    Ending how;
    std::vector<Vec2> line;
    int degree = 0;       // the junction its end makes (0: none counted, a boundary cut)
    int stub_taken = -1;  // Kind::node: the pending stub of that node it fills
    double cost = 0.0;
  };

  double outcome_cost(const Outcome& o) const {
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
  double opened_cost(const Outcome& o, const Piece& piece) const {
    if (!few_orientations_ || o.how.kind != Ending::Kind::free || piece.end_turns.empty())
      return 0.0;
    const double arrive = leaving(o.line, false) + kPi;
    double cost = 0.0;
    for (double turn : piece.end_turns) {
      const double h = arrive + turn;
      cost += excess(edge_bearing_, edge_count_, target_bearing_,
                     std::size_t(bearing_bin({std::cos(h), std::sin(h)})));
    }
    return kOpenedWeight * cost / double(piece.end_turns.size());
  }

  // `retry`: a stub that found nothing the first time, tried again once the region is covered
  // with more candidates and a straight link onto the network ahead (a junction left short of
  // its degree would become a bend or a dangling end).
  void grow_stub(const Stub& stub, bool retry = false) {
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
      if (auto o = evaluate(stub, link,
                            {origin, origin + Vec2{std::cos(stub.heading), std::sin(stub.heading)} *
                                                  link.length});
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
      for (Vec2 v : piece.points) pts.push_back(origin + rotate(v, stub.heading));
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
      for (Vec2 v : piece.points) pts.push_back(origin + rotate(v, stub.heading));
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

  // Whether one more end a gap short of a line keeps the output's share of them (per node
  // counted in the degree histogram) within the exemplar's.
  bool short_of_gap_ends() const {
    return (gap_ends_ + 1.0) / (junction_count_ + 1.0) <= gap_share_;
  }
  // Shortens a polyline by `by` metres at its end; false when nothing would be left.
  static bool cut_back(std::vector<Vec2>& pts, double by) {
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
  static void truncate(std::vector<Vec2>& pts, const Hit& hit) {
    pts.resize(hit.k + 1);
    if (!(pts.back() == hit.point)) pts.push_back(hit.point);
  }
  static void bend_end(std::vector<Vec2>& pts, Vec2 target) {
    const Vec2 d = target - pts.back();
    const double total = polyline_length(pts);
    double s = 0.0;
    for (std::size_t k = 1; k < pts.size(); ++k) {
      s += distance(pts[k - 1], pts[k]);
      pts[k] += d * (total > 0.0 ? s / total : 1.0);
    }
    pts.back() = target;
  }
  bool connected(int a, int b) const {
    for (int e : incident_[std::size_t(a)])
      if (alive_[std::size_t(e)] &&
          (out_.edges[std::size_t(e)].from == b || out_.edges[std::size_t(e)].to == b))
        return true;
    return false;
  }
  // The angle (radians, 0..pi/2) between the arriving line's last segment and an edge segment.
  static double meeting_angle(const std::vector<Vec2>& line, Vec2 a, Vec2 b) {
    const Vec2 u = normalized(line.back() - line[line.size() - 2]), v = normalized(b - a);
    return std::asin(std::min(1.0, std::abs(cross(u, v))));
  }
  // The pending stub of node n pointing closest to `towards` (radians), within 60°.
  int pending_stub(int n, double towards) const {
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
  std::optional<Outcome> evaluate(const Stub& stub, const Piece& piece, std::vector<Vec2> pts,
                                  Spacing spacing = Spacing::grown) {
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
    if (spacing == Spacing::laid_out && ending.kind == Ending::Kind::free &&
        piece.end_degree == 1) {
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

  void commit(const Stub& stub, const Piece& piece, Outcome o) {
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

  void push_stub(int node, double heading, int own_piece = -1) {
    const int id = int(stubs_.size());
    stubs_.push_back({node, heading, id, own_piece});
    cancelled_.push_back(0);
    stubs_of_[std::size_t(node)].push_back(id);
    queue_.push_back(stubs_.back());
  }

  void retry_failed() {
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

  void drain() {
    while (!queue_.empty()) {
      const Stub s = queue_.front();
      queue_.pop_front();
      grow_stub(s);
    }
  }

  // Seeds on a lattice over the region, in a seeded order, wherever the network has not reached.
  void seed_lattice() {
    const double spacing = median_;
    const BgPoint lo = extent_.min_corner(), hi = extent_.max_corner();
    const int nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / spacing)));
    const int ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / spacing)));
    std::vector<std::int64_t> order(std::size_t(nx) * std::size_t(ny));
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::int64_t(i);
    // Centre first (the network grows outward from one seed), the rest shuffled.
    const std::int64_t centre = std::int64_t(ny / 2) * nx + nx / 2;
    std::swap(order[0], order[std::size_t(centre)]);
    for (std::size_t i = order.size() - 1; i > 1; --i)
      std::swap(order[i], order[1 + rng_.below(i)]);
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

  // A straight link from node n along `heading` onto the first line ahead within `reach`, when
  // valid: the node becomes a junction.
  bool link_ahead(int n, double heading, double reach, int own_edge) {
    const Vec2 p = out_.nodes[std::size_t(n)];
    return link_along(n, {p, p + Vec2{std::cos(heading), std::sin(heading)} * reach}, own_edge);
  }

  // Node n joined along `ray` (a polyline from it) onto the first line it meets, when that is
  // valid.
  bool link_along(int n, std::vector<Vec2> ray, int own_edge) {
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
  void link_onto(int n, std::vector<Vec2> ray, const Hit& hit) {
    const int t = split_edge(hit.edge, hit.seg, ray.back());
    ray.back() = out_.nodes[std::size_t(t)];
    NetworkEdge link;
    link.from = n;
    link.to = t;
    link.points = std::move(ray);
    add_edge(std::move(link));
  }

  // Nodes left with two edges at a corner (a junction whose other stubs found nothing) would be
  // merged into a bent edge the exemplar does not have: one of the edges is continued straight
  // through the node onto the line ahead, making the corner a T-junction, when that is valid.
  void close_corners() {
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
  bool link_to_boundary(int n, double heading, double reach) {
    const Vec2 p = out_.nodes[std::size_t(n)];
    std::vector<Vec2> ray{p, p + Vec2{std::cos(heading), std::sin(heading)} * reach};
    const auto wall = first_boundary_hit(ray);
    if (!wall) return false;
    truncate(ray, *wall);
    if (first_edge_hit(ray) || polyline_length(ray) < min_piece_) return false;
    ray.back() = ray.back() +
                 (ray.front() - ray.back()) * std::min(0.5, 1e-9 * median_ / polyline_length(ray));
    if (!valid(ray, false)) return false;
    const int end = add_node(ray.back());
    out_.on_boundary[std::size_t(end)] = 1;
    NetworkEdge link;
    link.from = n;
    link.to = end;
    link.points = std::move(ray);
    add_edge(std::move(link));
    return true;
  }

  // Dangling ends beyond the exemplar's rate: joined onto the network straight ahead when a
  // short, valid link exists, else short dead ends are pruned.
  void close_dangling_ends() {
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
      const Vec2 p = out_.nodes[std::size_t(n)];
      std::vector<Vec2> ray{p, p + Vec2{std::cos(ahead), std::sin(ahead)} * (0.6 * median_)};
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
            ray.back() = out_.nodes[std::size_t(node)];
            NetworkEdge link;
            link.from = n;
            link.to = node;
            link.points = std::move(ray);
            add_edge(std::move(link));
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

  // ---- whole cells at the border --------------------------------------------------------------
  // An exemplar of closed cells, none cut (no dangling end, no end on a region's boundary: its
  // outermost cells are whole and their outer sides are its border), gets the same border: the
  // lines cut by the region's boundary are taken out back to their junctions, so that the
  // outermost cells left are whole and their outer sides, merged through the nodes that lost the
  // cut line, are the output's border.
  void keep_whole_cells() {
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
      border_node_.resize(out_.nodes.size(), 0);
      border_node_[std::size_t(trim_from(other, INFINITY))] = 1;
    }
  }

  // ---- straight edges -------------------------------------------------------------------------
  // An output edge as the network is written: alive edges merged through the nodes where exactly
  // two of them meet (neither kept), from every other node in order, then the cycles left; a kept
  // edge alone, as drawn.
  struct Chain {
    std::vector<int> edges;
    int from = -1, to = -1;
    std::vector<Vec2> points;
    bool kept = false;
  };
  std::vector<int> alive_incident(int n) const {
    std::vector<int> out;
    for (int e : incident_[std::size_t(n)])
      if (alive_[std::size_t(e)]) out.push_back(e);
    return out;
  }
  std::vector<Chain> chains() const {
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
  // headings and meets the other lines there at kMinMeetingAngle or more: kinks always, corners
  // while the output holds a larger share of bent edges than the exemplar (its few bent edges
  // are corners too: a frame's).
  void straighten_edges() {
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
    // The outermost cells' sides merged through the nodes that lost a cut line are the
    // exemplar's own kind of bend (its border's): they are kept.
    border_node_.resize(out_.nodes.size(), 0);
    const auto on_border = [&](const Chain& c) {
      for (int e : c.edges)
        for (int n : {out_.edges[std::size_t(e)].from, out_.edges[std::size_t(e)].to})
          if (n != c.from && n != c.to && border_node_[std::size_t(n)]) return true;
      return false;
    };
    // Steps shorter than kShortStep clearances (a snapped end's last hair) turn sharply over no
    // length: the exemplar's straight lines have none. `bent` still counts them (the corners'
    // pass below went on as long as before).
    for (const Chain& c : before)
      if (const std::vector<Vec2> tidy = without_short_steps(c.points);
          polyline_turning(tidy) + kStraightTurning < polyline_turning(c.points))
        replace_chain(c, tidy);
    before = chains();
    std::erase_if(before, [](const Chain& c) { return c.kept; });
    for (const Chain& c : before)
      if (double(bent) > allowed + 0.5 && sharpest_turn(c.points) >= kCornerTurn && !on_border(c) &&
          (straighten(c) || remove_corner(c, ends_allowed) || link_chain_corner(c)))
        --bent;
    // Kinks always (the junctions a removed corner left are straight through now).
    for (const Chain& c : chains())
      if (!c.kept && sharpest_turn(c.points) < kCornerTurn && polyline_turning(c.points) > 0.0)
        straighten(c);
  }
  // Points p with those less than kShortStep clearances past the last one kept, or short of the
  // end, left out (the ends stay).
  std::vector<Vec2> without_short_steps(const std::vector<Vec2>& p) const {
    std::vector<Vec2> out{p.front()};
    for (std::size_t k = 1; k + 1 < p.size(); ++k)
      if (distance(p[k], out.back()) >= kShortStep * clearance_ &&
          distance(p[k], p.back()) >= kShortStep * clearance_)
        out.push_back(p[k]);
    out.push_back(p.back());
    return out;
  }
  static double sharpest_turn(const std::vector<Vec2>& p) {
    double sharpest = 0.0;
    for (std::size_t k = 1; k + 1 < p.size(); ++k)  // as polyline_turning (repeated points)
      sharpest = std::max(sharpest, polyline_turning({p[k - 1], p[k], p[k + 1]}));
    return sharpest;
  }

  // How many dead ends taking chain `c` off leaves at its end node n (0 or 1), or -1 when that
  // is not allowed: n is left a junction still, a line going straight through it (within a
  // stroke's deflection) or a dead end; a cut end on the boundary goes with its line.
  int ends_left_at(int n, const Chain& c) const {
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
  void take_off(const Chain& c) {
    for (int e : c.edges) {
      index_edge(e, false);
      alive_[std::size_t(e)] = 0;
      --degree_[std::size_t(out_.edges[std::size_t(e)].from)];
      --degree_[std::size_t(out_.edges[std::size_t(e)].to)];
      ++report_.pruned;
    }
    forget_passed_nodes(c);
  }

  // A corner its chord cannot replace is taken out whole, junction to junction, when both its
  // end nodes allow it (ends_left_at) and the dead ends left are within the exemplar's rate
  // (`ends_allowed`, spent); else one leg is taken off at the corner (the shorter first), the
  // corner becoming a dead end, the other leg kept as it lies.
  bool remove_corner(const Chain& c, int& ends_allowed) {
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
      std::vector<Vec2> kept = side == 0
                                   ? std::vector<Vec2>(p.begin() + long(corner), p.end())
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
  bool link_chain_corner(const Chain& c) {
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
              link_to_boundary(n, h[k] + kPi, kChainCornerReach * median_))
            return true;
      }
    return false;
  }
  // The nodes a chain passed through, left without edges, are no seeds to keep clear of.
  void forget_passed_nodes(const Chain& c) {
    for (int e : c.edges) {
      const NetworkEdge& edge = out_.edges[std::size_t(e)];
      for (int n : {edge.from, edge.to})
        if (n != c.from && n != c.to && degree_[std::size_t(n)] == 0)
          nodes_.remove(NodeValue{to_bg(out_.nodes[std::size_t(n)]), n});
    }
  }

  bool straighten(const Chain& c) {
    const std::vector<Vec2> chord{c.points.front(), c.points.back()};
    if (polyline_length(chord) < min_piece_) return false;
    for (int end = 0; end < 2; ++end) {
      const int n = end == 0 ? c.from : c.to;
      const double old_heading = leaving(c.points, end == 0),
                   new_heading = leaving(chord, end == 0);
      if (std::abs(wrap(new_heading - old_heading)) > kStraightenDeflection) return false;
      for (int other : alive_incident(n)) {
        if (std::find(c.edges.begin(), c.edges.end(), other) != c.edges.end()) continue;
        const NetworkEdge& e = out_.edges[std::size_t(other)];
        if ((e.from == c.from && e.to == c.to) || (e.from == c.to && e.to == c.from)) return false;
        const double h = leaving(e.points, e.from == n);
        if (std::abs(wrap(h - new_heading)) < kMinMeetingAngle) return false;
      }
    }
    return replace_chain(c, chord);
  }
  // Chain c replaced by `line` (same ends) when that is committed under the rules the line it
  // replaces kept: a copy of exemplar lines (quilt, layout) keeps the exemplar's own spacing near
  // its junctions, a grown piece the clearance there too.
  bool replace_chain(const Chain& c, const std::vector<Vec2>& line) {
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
  Network finish() {
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

  const Network& exemplar_;
  const ForbiddenMask* forbidden_;
  Raster<std::uint8_t> dilated_;
  std::map<std::pair<double, double>, int> node_at_;  // quilt nodes by their exact place
  NetworkGrowthOptions options_;
  NetworkGrowthReport& report_;
  SplitMix64 rng_;

  std::vector<Piece> pieces_;
  // The exemplar's dangling ends within the clearance of another line, per node (its gaps),
  // and how many of them the output has.
  double gap_share_ = 0.0, gap_ends_ = 0.0;
  bool few_orientations_ = false;  // its edges run at few orientations (kFewOrientations)
  std::vector<int> gap_pieces_;    // the pieces that end a gap short of a line (ends_at_line)
  std::vector<int> piece_of_;      // per exemplar edge and direction (2 i + dir): its piece or -1
  std::vector<int> junctions_;
  std::vector<std::vector<double>> junction_headings_;
  double median_ = 1.0, clearance_ = 0.0, snap_ = 0.0, min_piece_ = 0.0, turn_ = 0.0;
  double seed_room_ = 0.0;       // seed_lattice: the room a seed needs (metres)
  int line_meeting_degree_ = 3;  // a line ending on another makes a T (3) or crosses it (4)
  std::vector<double> length_edges_;
  std::array<double, 7> target_degree_{}, have_degree_{};
  std::array<double, 12> target_bearing_{}, have_bearing_{}, edge_bearing_{};
  double edge_count_ = 0.0;
  network_detail::BearingCdf bearing_cdf_;
  std::array<double, 12> target_length_{}, have_length_{};
  double grown_length_ = 0.0, length_per_junction_ = 1.0;
  double junctions() const {
    double n = 0.0;
    for (std::size_t d = 3; d < have_degree_.size(); ++d) n += have_degree_[d];
    return n;
  }
  double placed_ = 0.0, junction_count_ = 0.0, dangling_target_ = 0.0;
  double straight_share_ = 0.0;    // of the exemplar's edges, those turning under kStraightTurning
  std::vector<char> border_node_;  // per node: it lost a line cut by the region (keep_whole_cells)
  bool whole_cells_ = false;  // the exemplar's cells are all closed, none cut (keep_whole_cells)
  bool completing_ = false;   // a partial network is kept (add_partial)
  int exemplar_nodes_ = 0;

  BgMultiPolygon region_;
  BgBox extent_;
  bgi::rtree<BgSegment, bgi::quadratic<16>> boundary_;
  bgi::rtree<SegValue, bgi::quadratic<16>> segments_;
  // The layout's copies of the exemplar (their empty parts get no lattice seed).
  std::optional<network_detail::LayoutCopies> layout_copies_;
  bgi::rtree<NodeValue, bgi::quadratic<16>> nodes_;

  Network out_;
  std::vector<int> degree_, planned_;
  std::vector<std::vector<int>> incident_, stubs_of_;
  std::vector<Stub> stubs_, failed_;
  std::vector<char> cancelled_;
  std::vector<char> alive_;
  std::deque<Stub> queue_;
};

}  // namespace

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
