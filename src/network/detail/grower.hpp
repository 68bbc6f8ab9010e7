#pragma once
// The grower behind grow_network (network/growth.hpp): its state and the declarations of its
// parts, defined by concern in growth.cpp (entry points, frontier growth), grower_exemplar.cpp
// (what it learns; the region), grower_rules.cpp (the network so far; the rules a line keeps),
// grower_layout.cpp, grower_quilt.cpp (quilting; links and trimming), grower_straighten.cpp,
// grower_bends.cpp (bends eased to the exemplar's), grower_twigs.cpp (a forest's twigs) and
// grower_junction_shift.cpp (junctions shifted for the bearings).
// Internal to the network module.

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "core/boost_geometry.hpp"
#include "core/split_mix.hpp"
#include "network/detail/bearing_cdf.hpp"
#include "network/detail/cell_cycles.hpp"
#include "network/detail/layout_copies.hpp"
#include "network/detail/skeleton.hpp"
#include "network/growth.hpp"

namespace tw::network_detail {

using namespace geometry;
using SegValue = std::pair<BgSegment, int>;  // a segment of an edge (its index)
using NodeValue = std::pair<BgPoint, int>;
using BgMultiPolygon = bg::model::multi_polygon<BgPolygon>;
constexpr double kPi = std::numbers::pi;

inline Vec2 vec(const BgPoint& p) {
  return {p.x(), p.y()};
}
inline double heading(Vec2 v) {
  return std::atan2(v.y, v.x);
}
inline double wrap(double a) {  // (-pi, pi]
  a = std::fmod(a + kPi, 2 * kPi);
  if (a <= 0) a += 2 * kPi;
  return a - kPi;
}

// A chord's bearing from north, modulo 180° (degrees), as network_stats measures it.
inline double chord_bearing(Vec2 chord) {
  return std::fmod(std::atan2(chord.x, chord.y) * 180.0 / kPi + 360.0, 180.0);
}

// Bearing bin (15°, 0..11) of a chord, from north, modulo 180°.
inline int bearing_bin(Vec2 chord) {
  return std::min(11, int(chord_bearing(chord) / 15.0));
}

// First distinct-point heading leaving an end of a polyline.
inline double leaving(const std::vector<Vec2>& pts, bool from_start) {
  return leaving_heading(pts, from_start);
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

// How far (radians) a straightened or eased edge may leave its junctions off its old heading
// there (Grower::straighten, Grower::ease_sharp_bends).
constexpr double kStraightenDeflection = 1.0;

// The weight of the bearings of the stubs a free end opens in a candidate's cost (opened_cost),
// and the share of the exemplar's edges in its two main 15° bearing bins from which it counts
// (a grid's tracks and field boundaries: nearly all).
constexpr double kOpenedWeight = 3.0;
constexpr double kFewOrientations = 0.75;

// A forest's branch junction opening stubs where the output's bearing distribution is ahead of the
// exemplar's costs more, by this (BearingCdf::step_cost of each stub, averaged; opened_cost).
constexpr double kForestOpenedWeight = 1.0;

// An edge turning less than this in all (radians) is straight; an exemplar whose edges are at
// least kStraightShare straight gets straight output edges (Grower::straighten_edges).
constexpr double kStraightTurning = 0.01;
constexpr double kStraightShare = 0.9;

// An exemplar whose degree-3 junctions are at least this share T-junctions (a line going on
// through within kStrokeDeflection) gets its large cells split by square chords, which make Ts
// (Grower::split_large_cells); one whose lines meet in Ys has no 180° gap for a chord to copy.
constexpr double kTJunctionShare = 0.1;

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

  void add_partial(const Network& partial);

  enum class Mode { grow, quilt, layout };
  Network run(Mode mode);

 private:
  // ---- the exemplar (grower_exemplar.cpp) -------------------------------------------------------
  void learn(const Network& ex);

  static std::vector<char> dangling_at_line(const Network& ex, const std::vector<int>& degree,
                                            double reach);

  // ---- the region (grower_exemplar.cpp) ---------------------------------------------------------
  void set_region(const std::vector<Polygon>& region);

  bool inside_region(Vec2 p) const { return bg::covered_by(to_bg(p), region_); }
  bool near_boundary(Vec2 p) const;

  void dilate_forbidden();
  bool forbidden_at(Vec2 p, bool dilated) const {
    if (!forbidden_) return false;
    const Vec2 px = forbidden_->grid.world_to_pixel(p);
    const int c = int(std::floor(px.x)), r = int(std::floor(px.y));
    const Raster<std::uint8_t>& m = dilated ? dilated_ : forbidden_->cells;
    return m.inside(c, r) && m.at(c, r) != 0;
  }
  bool enters_forbidden(const std::vector<Vec2>& pts) const;

  // ---- the network so far, the rules a line keeps (grower_rules.cpp) ----------------------------
  int add_node(Vec2 p);
  void index_edge(int id, bool insert);
  int add_edge(NetworkEdge e);
  void count_edge_bearing(const std::vector<Vec2>& pts, double count);
  int split_edge(int id, int seg, Vec2 p);

  // A straight ray from node n along `heading`, `reach` long: what each link from a node tries.
  std::vector<Vec2> ray_from(int n, double heading, double reach) const {
    const Vec2 p = out_.nodes[std::size_t(n)];
    return {p, p + Vec2{std::cos(heading), std::sin(heading)} * reach};
  }
  std::optional<Hit> first_edge_hit(const std::vector<Vec2>& pts) const;
  std::optional<Hit> first_boundary_hit(const std::vector<Vec2>& pts) const;

  bool valid(const std::vector<Vec2>& pts, bool end_joint, Spacing spacing = Spacing::grown,
             double joint_slack = 0.0);

  bool edge_meets(int id, const std::vector<Vec2>& joints) const;
  bool clear_of_lines(Vec2 p) const;
  void count_line(const std::vector<Vec2>& pts);
  std::vector<std::vector<Vec2>> inside_parts(std::vector<Vec2> pts) const;
  bool place_line(std::vector<Vec2> pts, double joint_slack = 0.0,
                  Spacing spacing = Spacing::copied);

  // ---- layout (docs/networks.md, "Layout"; grower_layout.cpp) -----------------------------------
  bool lay_out_long_strokes();

  // ---- quilting, links, trimming (docs/networks.md, "Quilting"; grower_quilt.cpp) ---------------
  void quilt();

  int trim_from(int n, double at_most);
  bool link_ahead(int n, double heading, double reach, int own_edge);
  bool link_along(int n, std::vector<Vec2> ray, int own_edge);
  void link_onto(int n, std::vector<Vec2> ray, const Hit& hit);
  void link_to(int n, std::vector<Vec2> ray, int to);
  void close_corners();
  bool link_to_boundary(int n, double heading, double reach);
  void close_dangling_ends();

  // ---- growth (growth.cpp) ----------------------------------------------------------------------
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

  double outcome_cost(const Outcome& o) const;

  double opened_cost(const Outcome& o, const Piece& piece) const;

  void grow_stub(const Stub& stub, bool retry = false);

  // Whether one more end a gap short of a line keeps the output's share of them (per node
  // counted in the degree histogram) within the exemplar's.
  bool short_of_gap_ends() const {
    return (gap_ends_ + 1.0) / (junction_count_ + 1.0) <= gap_share_;
  }
  static bool cut_back(std::vector<Vec2>& pts, double by);
  static void truncate(std::vector<Vec2>& pts, const Hit& hit) {
    pts.resize(hit.k + 1);
    if (!(pts.back() == hit.point)) pts.push_back(hit.point);
  }
  static void bend_end(std::vector<Vec2>& pts, Vec2 target);
  bool connected(int a, int b) const {
    for (int e : incident_[std::size_t(a)])
      if (alive_[std::size_t(e)] &&
          (out_.edges[std::size_t(e)].from == b || out_.edges[std::size_t(e)].to == b))
        return true;
    return false;
  }
  static double meeting_angle(const std::vector<Vec2>& line, Vec2 a, Vec2 b);
  int pending_stub(int n, double towards) const;

  std::optional<Outcome> evaluate(const Stub& stub, const Piece& piece, std::vector<Vec2> pts,
                                  Spacing spacing = Spacing::grown);

  void commit(const Stub& stub, const Piece& piece, Outcome o);

  void push_stub(int node, double heading, int own_piece = -1);

  void retry_failed();

  void drain();

  void seed_lattice();

  // ---- whole cells at the border (grower_quilt.cpp) ---------------------------------------------
  void keep_whole_cells();

  // ---- cells larger than the exemplar's split, smaller merged (grower_cells.cpp) ----------------
  void split_large_cells(CellCycles& cells);
  bool merge_small_cells(CellCycles& cells);

  // ---- straight edges (grower_straighten.cpp) ---------------------------------------------------
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
  std::vector<Chain> chains() const;
  bool still_a_chain(const Chain& c) const;
  bool on_border(const Chain& c) const;

  void straighten_edges();
  void straighten_kinks();
  std::vector<Vec2> without_short_steps(const std::vector<Vec2>& p) const;
  bool without_end_jogs(const Chain& c);
  static double sharpest_turn(const std::vector<Vec2>& p);

  int ends_left_at(int n, const Chain& c) const;
  void take_off(const Chain& c);

  bool remove_corner(const Chain& c, int& ends_allowed);
  bool link_chain_corner(const Chain& c);
  bool link_to_passed_node(int n, double heading, double reach);
  void forget_passed_nodes(const Chain& c);

  bool straighten(const Chain& c);
  bool replace_chain(const Chain& c, const std::vector<Vec2>& line);
  bool ends_meet_lines(const Chain& c, const std::vector<Vec2>& line, double min_angle) const;

  // ---- bends as sharp as the exemplar's (grower_bends.cpp) --------------------------------------
  void ease_sharp_bends();
  bool ease(const Chain& c);

  // ---- a forest's twigs (grower_twigs.cpp) ------------------------------------------------------
  void prune_twigs_for_bearings();
  // ---- junctions shifted for bearings (grower_junction_shift.cpp) -------------------------------
  void shift_junctions_for_bearings();

  Network finish();

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
  BearingCdf bearing_cdf_;
  std::array<double, 12> target_length_{}, have_length_{};
  double grown_length_ = 0.0, length_per_junction_ = 1.0;
  double junctions() const {
    double n = 0.0;
    for (std::size_t d = 3; d < have_degree_.size(); ++d) n += have_degree_[d];
    return n;
  }
  double placed_ = 0.0, junction_count_ = 0.0, dangling_target_ = 0.0;
  double straight_share_ = 0.0;   // of the exemplar's edges, those turning under kStraightTurning
  double max_cell_area_ = 0.0;    // its largest cell, where its cells are closed and straight
  double min_cell_area_ = 0.0;    // and its smallest
  bool cells_end_in_ts_ = false;  // and its lines end on each other in Ts (split_large_cells)
  bool forest_ = false;           // its lines end free (dangling ends a third of its nodes or more)
  // Where the exemplar's edges are at least kStraightShare straight: how much its other (bent)
  // edges turn per metre, on average and at most (ease_sharp_bends; 0 when it has none), and its
  // narrowest angle between lines at a junction (radians; straighten).
  double bend_curvature_mean_ = 0.0, bend_curvature_max_ = 0.0, narrowest_junction_ = 0.0;
  // A forest's own samples, as network_stats has them (bearings turned by the lead bearing), that
  // prune_twigs_for_bearings keeps the output near.
  std::vector<double> exemplar_bearings_, exemplar_degrees_, exemplar_curvature_;
  double own_degree_apart_ = 0.0, own_curvature_apart_ = 0.0;  // its halves' distances
  std::vector<char> border_node_;  // per node: it lost a line cut by the region (keep_whole_cells)
  bool whole_cells_ = false;  // the exemplar's cells are all closed, none cut (keep_whole_cells)
  bool completing_ = false;   // a partial network is kept (add_partial)
  int exemplar_nodes_ = 0;

  BgMultiPolygon region_;
  BgBox extent_;
  bgi::rtree<BgSegment, bgi::quadratic<16>> boundary_;
  bgi::rtree<SegValue, bgi::quadratic<16>> segments_;
  // The layout's copies of the exemplar (their empty parts get no lattice seed).
  std::optional<LayoutCopies> layout_copies_;
  bgi::rtree<NodeValue, bgi::quadratic<16>> nodes_;

  Network out_;
  std::vector<int> degree_, planned_;
  std::vector<std::vector<int>> incident_, stubs_of_;
  std::vector<Stub> stubs_, failed_;
  std::vector<char> cancelled_;
  std::vector<char> alive_;
  std::deque<Stub> queue_;
  // While cells are split and merged: told of every edit (split_edge, link_to, take_off).
  CellCycles* cell_cycles_ = nullptr;
};

}  // namespace tw::network_detail
