#pragma once
// The network stage of a run (docs/networks.md, "In pipelines"): after the grown classes, every
// class with a `network:` block gets a curve network grown by example over its region, off the
// existing features and the lines of the classes before it; its edges are the class's lines
// from then on (ribbons, junctions, profiles, synthesis, exports), grown once in the plan.
#include <optional>
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/methods/network/network_report.hpp"

namespace tw::detail {

// Fills lines[c] of every network class c (FID n: the n-th edge, from 1) and its report
// reports[c] (one per class), its edges kept out of `reserved` (the polygons the other methods keep
// for themselves: the area classes') where the class avoids. Deterministic with each class's
// network.seed. Throws tw::Error naming features.<class>.network.<key> on a bad exemplar, region or
// partial network, and on any crossing the GEOS check finds.
void grow_network_classes(const std::vector<FeatureClassConfig>& classes,
                          const HeightfieldSource& source, const Heightfield& heightfield,
                          const ExistingFeatures& existing, const std::vector<Polygon>& reserved,
                          std::vector<std::vector<LineFeature>>& lines,
                          std::vector<std::optional<NetworkClassReport>>& reports,
                          Warnings& warnings);

}  // namespace tw::detail
