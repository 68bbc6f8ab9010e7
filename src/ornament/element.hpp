#pragma once
// FloralSurf's decorative elements (Albano et al. 2023, Section 3.1): cubic Bézier splines in a
// 2-D reference frame, with growth points from which an ornament grows further. The frame's
// origin is where the element attaches and +x is the growth direction; one unit is `scale_m`
// metres on the terrain. docs/ornaments.md describes the JSON format.
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

// A cubic Bézier spline: 3n + 1 control points (n >= 1 segments sharing their end points).
struct BezierSpline {
  std::string material;  // what the line becomes: "hedge", "wall", "gate", ...
  std::vector<Vec2> control_points;
};

// Where an ornament may grow on: a point on the element and a direction (radians, from the
// element's +x axis), with the tag of the elements that may grow there.
struct GrowthPoint {
  std::string tag;
  Vec2 at;
  double angle = 0.0;
  int priority = 0;  // higher grows first (the paper's priority queue)
};

struct DecorativeElement {
  std::string name;
  std::string tag;  // the growth points this element answers
  std::vector<BezierSpline> splines;
  std::vector<GrowthPoint> growth_points;
  std::vector<double> sizes{1.0};  // scale factors drawn at random per candidate
  double rotation_jitter = 0.0;    // radians: a candidate turns by up to this either way
};

struct ElementSet {
  std::string name;
  std::string kind;          // hedge | wall | trail | ditch: the line class the ornaments become
  std::string seed_tag;      // the tag of the elements that start an ornament
  double scale_m = 10.0;     // metres per reference unit
  double clearance_m = 0.0;  // least distance between unrelated ornament lines
  std::vector<DecorativeElement> elements;
};

// Reads and validates an element set; throws tw::Error naming the file and the key at fault.
ElementSet read_element_set(const std::filesystem::path& path);
// The same from JSON text; `origin` names it in errors.
ElementSet parse_element_set(const std::string& json, const std::string& origin);

// The elements whose tag is `tag`, by index into set.elements.
std::vector<int> elements_with_tag(const ElementSet& set, const std::string& tag);

// A spline as a polyline in its reference frame (planar de Casteljau, `per_segment` points per
// cubic segment): previews and tests.
std::vector<Vec2> planar_polyline(const BezierSpline& spline, int per_segment = 16);

}  // namespace tw
