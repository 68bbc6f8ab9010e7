#pragma once
// What the network method reports of a run (report.json: a network class's `network`;
// docs/networks.md, "In pipelines"): its part of the run's report (pipeline/method_report.hpp),
// which it writes into report.json and the plan folder itself.
#include <optional>
#include <string>
#include <vector>

#include "pipeline/method_report.hpp"
#include "pipeline/run.hpp"

namespace tw::detail {

// A network class's growth (network/growth.hpp's counts).
struct NetworkClassReport {
  std::string exemplar;        // "path[:layer]" or the .svg
  std::string method, chosen;  // network.method as asked; what made the lines (never automatic)
  // network.lead ("" without one) and the compass bearing it gave over the region.
  std::string lead;
  double lead_bearing_deg = 0.0;
  int exemplar_edges = 0, lines = 0, kept = 0;  // kept: the partial drawing's edges
  int placed = 0, snapped = 0, t_junctions = 0, boundary_ends = 0, pruned = 0;
  int rejected_crossing = 0, rejected_region = 0, rejected_forbidden = 0;
};

struct NetworkReport : MethodPayloadOf<NetworkReport> {
  std::vector<std::optional<NetworkClassReport>> classes;  // per class of the run
};

// Class c's network in a run's report; null when it is not a network class.
inline const NetworkClassReport* network_class_report(const RunReport& report, std::size_t c) {
  const NetworkReport* part = method_report<NetworkReport>(report);
  return part && c < part->classes.size() && part->classes[c] ? &*part->classes[c] : nullptr;
}

}  // namespace tw::detail
