#pragma once
// What the grown method reports of a run (report.json: a grown class's `grow` and `grown_kind`,
// `grown_crossings`; docs/pipeline.md, "Grown classes"): its part of the run's report
// (pipeline/method_report.hpp), which it writes into report.json and the plan folder itself.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/method_report.hpp"
#include "pipeline/run.hpp"

namespace tw::detail {

// Grown lines that cross (docs/ornaments.md, "Crossings"): checked exactly on the lines
// written; 0, or the run fails.
struct GrownCrossings {
  std::int64_t grown = 0;      // pairs of grown lines (crossing in a class, overlapping across)
  std::int64_t feature = 0;    // (grown line, feature read) footprints overlapping
  std::int64_t forbidden = 0;  // grown lines through a nodata cell
};

// A grown class: what the space filling placed, the candidates it refused by reason, and the
// coverage (the fraction of the region's allowed mesh vertices within coverage_radius_m,
// geodesic, of a line). Its `synthesis:` counts are the patterns' (pattern_report.hpp).
struct GrowthReport {
  std::string kind;     // hedge, wall, trail, ditch (or the line kind given with grow:)
  std::string element;  // the element set
  int ornaments = 0, elements = 0, lines = 0;
  int rejected_crossing = 0, rejected_forbidden = 0, rejected_untraceable = 0;
  int rejected_footprint = 0;  // candidates onto a footprint, exactly (vector space)
  GrownCrossings crossings;
  double coverage = 0.0, coverage_radius_m = 0.0;
  int mesh_width = 0, mesh_height = 0;  // vertices (the time is the stage `grow`'s)
  int short_lines = 0;  // lines shorter than one piece (delta): no ribbon, no pattern
};

struct GrownReport : MethodPayloadOf<GrownReport> {
  std::vector<std::optional<GrowthReport>> classes;  // per class of the run: the grown ones
  std::int64_t crossings = 0;  // summed over the grown classes (0, or the run fails)
};

// Class c's growth in a run's report; null when it is not a grown class.
inline const GrowthReport* growth_report(const RunReport& report, std::size_t c) {
  const GrownReport* part = method_report<GrownReport>(report);
  return part && c < part->classes.size() && part->classes[c] ? &*part->classes[c] : nullptr;
}

}  // namespace tw::detail
