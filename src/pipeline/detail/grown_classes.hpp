#pragma once
// The growth stage of a run (docs/pipeline.md, "Grown classes"): between ingest and ribbons,
// every class with a `grow:` block gets its lines grown over its region (FloralSurf,
// docs/ornaments.md), in class order, each off the existing features, the read classes' lines
// and the lines grown before it (their footprints, widened by its own width). From then on the
// lines are the class's features like any other: ribbons, terrain, synthesis.
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

// Fills lines[c] of every grown class c (FID n: the n-th line grown, from 1), its report's
// `grow` and the plan's GrownClass. Deterministic with each class's grow.seed. Throws
// tw::Error naming features.<class> (and the file or key) on a bad element set or region.
std::vector<GrownClass> grow_classes(const PipelineConfig& config, const HeightfieldSource& source,
                                     const Heightfield& heightfield,
                                     const ExistingFeatures& existing,
                                     std::vector<std::vector<LineFeature>>& lines,
                                     std::vector<FeatureClassReport>& reports, Warnings& warnings);

}  // namespace tw::detail
