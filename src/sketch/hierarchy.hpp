#pragma once
// The Support Structure Hierarchy (Olivier, Memari & Cani, Section 4): strokes -> shapes
// (level 0) -> fibres and their ribbons (level 1) -> fibre medians (level 2) -> lead directions
// (level 3), with the allowed displacement areas that keep repeated structures apart.
#include <vector>

#include "core/vec2.hpp"
#include "sketch/sketch.hpp"

namespace tw {

// A line through `point` with unit `direction`, its angle folded into [0, pi).
struct SupportLine {
  Vec2 point;
  Vec2 direction{1.0, 0.0};
};

struct OrientedBox {
  Vec2 center;
  Vec2 axis{1.0, 0.0};  // unit, the principal direction (PCA)
  double half_length = 0.0;
  double half_width = 0.0;
};

enum class ShapeSupport {
  point,    // bounded, nearly isotropic: its central point
  segment,  // bounded, anisotropic: its support segment along the box axis
  fibre,    // unbounded: a fibre of its own
};

// How an unbounded stroke is extended beyond the input space (Section 5, Fig. 8).
enum class UnboundedCategory { line, ray, arc, curve };

struct SketchShape {
  std::vector<int> strokes;  // indices into Sketch::strokes
  ShapeSupport support = ShapeSupport::point;
  UnboundedCategory category = UnboundedCategory::line;  // unbounded shapes only
  OrientedBox box;  // of every point of its strokes, thickness included
};

// An interval of offsets along a parent structure's normal (ribbons) or axis (shapes).
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

struct Fibre {
  SupportLine line;
  std::vector<int> shapes;  // sorted along the line
  bool unbounded = false;
  Interval extent;  // of its shapes' contents, across `line` (offsets from line.point)
  // Bounded fibres: the shapes' extents along the line and the gaps between them, the last gap
  // wrapping around the input space (its toroidal topology).
  std::vector<Interval> along;
  std::vector<double> gaps_along;
};

// Level 2 and 3 structures: a direction with the sub-structures it groups, their contents'
// extents across it, and the gaps between neighbours (sorted by offset).
struct Grouping {
  SupportLine line;
  std::vector<int> members;             // fibres of a median, medians of a lead direction
  std::vector<Interval> extents;        // per member, offsets across `line`
  double gap_min = 0.0, gap_max = 0.0;  // between neighbouring members (0, 0 with one member)
  double angle_sd = 0.0;                // circular standard deviation of the members' angles
};

struct SupportHierarchy {
  Sketch sketch;
  std::vector<SketchShape> shapes;  // level 0
  std::vector<Fibre> fibres;        // level 1
  std::vector<Grouping> medians;    // level 2 (members: fibres)
  std::vector<Grouping> leads;      // level 3 (members: medians)
};

struct AnalysisParams {
  double group_distance = 0.02;    // bounded strokes closer than this form one shape
  double anisotropy = 2.0;         // half_length / half_width above which a shape is a segment
  double angle_bandwidth = 0.2;    // radians: orientation clusters (segments, medians, leads)
  double offset_bandwidth = 0.04;  // input-space units: mean shift on line offsets
  double median_distance = 0.06;   // the paper's perceived distance below which fibres merge
};

// Fine-to-coarse analysis of a checked sketch. Deterministic.
SupportHierarchy analyze_sketch(const Sketch& sketch, const AnalysisParams& params = {});

// The paper's perceived distance between two lines (Fig. 3): the least distance between their
// intersections with any of the input space's border lines X = 0, X = 1, Y = 0, Y = 1.
double perceived_distance(const SupportLine& a, const SupportLine& b);

// Angle of a direction folded into [0, pi).
double line_angle(Vec2 direction);

}  // namespace tw
