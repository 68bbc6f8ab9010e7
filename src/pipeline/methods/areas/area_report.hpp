#pragma once
// What the areas method reports of a run (report.json `areas`; docs/shape-patterns.md): its
// part of the run's report (pipeline/method_report.hpp), which it writes into report.json and
// the plan folder itself.
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/method_report.hpp"
#include "pipeline/run.hpp"

namespace tw::detail {

// One polygon of a `kind: area` class: what was placed, the candidates left out by reason, and
// the pixels its strokes cover that the avoidance map forbids (0: the synthesis kept off them,
// checked independently on the canvas).
struct AreaFeatureReport {
  std::int64_t fid = 0;
  double area_m2 = 0.0;
  double lead_bearing_deg = 0.0;  // compass bearing of the sketch's +x axis
  std::uint64_t seed = 0;
  int shapes = 0, strokes = 0;
  int outside = 0, forbidden = 0, overlapping = 0;
  std::int64_t forbidden_touched = 0;
  int on_nodata = 0;  // shapes left out: their instance stood on nodata heights
  // Cells of the polygon's avoidance canvas allocated at its peak: they follow the polygon's
  // area (and a band along its boundary), not its box.
  std::int64_t canvas_cells = 0;
};

struct AreaClassReport {
  std::string name;
  std::string source;  // path:layer
  std::string sketch;
  std::string lead;                         // bearing, long_axis, nearest_road or contours
  std::vector<AreaFeatureReport> features;  // in reading order (a multi-part FID repeats)
};

struct AreasReport : MethodPayloadOf<AreasReport> {
  std::vector<AreaClassReport> classes;  // the `kind: area` classes, in config order
};

// The area classes' reports in a run's report (empty: none).
inline const std::vector<AreaClassReport>& area_reports(const RunReport& report) {
  static const std::vector<AreaClassReport> none;
  const AreasReport* part = method_report<AreasReport>(report);
  return part ? part->classes : none;
}

}  // namespace tw::detail
