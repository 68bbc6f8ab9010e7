#pragma once
// The growth stage of a run (docs/pipeline.md, "Grown classes"): between ingest and ribbons,
// every class with a `grow:` block gets its lines grown over its region (FloralSurf,
// docs/ornaments.md), in class order, each off the existing features, the read classes' lines
// and the lines grown before it (their footprints, widened by its own width). From then on the
// lines are the class's features like any other: ribbons, terrain, synthesis.
#include <map>
#include <optional>
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield_source.hpp"
#include "ornament/grow.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/methods/grown/grown_method.hpp"
#include "pipeline/methods/grown/grown_report.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

// Fills lines[c] of every grown class c (FID n: the n-th line grown, from 1), its report
// reports[c] (one per class) and the plan's GrownClass. Deterministic with each class's grow.seed.
// Throws tw::Error naming features.<class> (and the file or key) on a bad element set or region.
std::vector<GrownClass> grow_classes(const std::vector<FeatureClassConfig>& classes,
                                     const HeightfieldSource& source,
                                     const Heightfield& heightfield,
                                     const ExistingFeatures& existing,
                                     std::vector<std::vector<LineFeature>>& lines,
                                     std::vector<std::optional<GrowthReport>>& reports,
                                     Warnings& warnings);

// The safety net after growth (docs/ornaments.md, "Crossings"): the grown lines (what
// ornaments.gpkg gets) checked exactly against each other, the lines of the classes read and the
// existing features, and each grown class's nodata cells (by class index; none if absent).
// Fills each grown class's report's `crossings` (reports: one per class); throws tw::Error counting
// them and naming the first few lines when any is non-zero (a growth bug: the run fails, nothing is
// written).
void check_grown_lines(const std::vector<FeatureClassConfig>& classes,
                       const ExistingFeatures& existing,
                       const std::vector<std::vector<LineFeature>>& lines,
                       const std::vector<GrownClass>& grown,
                       const std::map<std::size_t, std::optional<ForbiddenCells>>& cells,
                       std::vector<std::optional<GrowthReport>>& reports);

}  // namespace tw::detail
