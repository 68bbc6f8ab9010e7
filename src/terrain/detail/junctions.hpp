#pragma once
// Where a feature's open end touches another feature of the same kind: shared endpoints
// (A ends where B ends or starts) and T-junctions (A ends on B's interior).
#include <vector>

#include "terrain/features.hpp"

namespace tw::detail {

struct EndContact {
  bool at_start = false;   // which end of the feature: its first point (true) or its last
  int other = 0;           // index of the touched feature
  double other_s = 0.0;    // arc length of the touch on the other feature
  bool other_end = false;  // the touch is at one of the other's ends (not its interior)
};

// For each feature, the contacts of its two ends with other features of the same kind,
// within half the wider width plus `tolerance` metres. Deterministic order (by feature).
std::vector<std::vector<EndContact>> find_end_contacts(const std::vector<TerrainFeature>& features,
                                                       double tolerance);

}  // namespace tw::detail
