#pragma once
// The area stage of a run (docs/shape-patterns.md): every polygon of a `kind: area` class gets
// the shape-pattern of its sketch (sketch/area_synthesis.hpp), laid along its lead direction, on
// an avoidance map of the synthesis lattice over the polygon's box: existing features, every
// line feature's footprint, junction discs, the curve patterns' opaque coverage and the strokes
// of the areas before it.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/methods/areas/area_config.hpp"
#include "pipeline/methods/areas/area_method.hpp"
#include "pipeline/methods/areas/area_report.hpp"
#include "pipeline/plan.hpp"
#include "raster/sparse_raster.hpp"
#include "sketch/hierarchy.hpp"

namespace tw::detail {

// The polygons of each area class (in order), read on the heightfield's grid (clipped to it,
// repaired with warnings naming the FID). Errors name features.<class>.
std::vector<std::vector<PolygonFeature>> load_area_polygons(
    const std::vector<AreaClassConfig>& areas, const Heightfield& heightfield, Warnings& warnings);

// The class's sketch (and its `shapes_from` donor) loaded and analysed: the Support Structure
// Hierarchy it is synthesized from. Throws tw::Error naming features.<class>, the sketch file
// and the FID of the stroke it cannot use.
SupportHierarchy area_hierarchy(const AreaClassConfig& area);

// What `terraweave validate` checks of the areas without synthesizing them: every class's
// sketches analysed (area_hierarchy's errors), its `materials` and `height` keys matched against
// the sketch's stroke materials (a warning for each the sketch lacks).
void check_area_sketches(const std::vector<AreaClassConfig>& areas, Warnings& warnings);

struct AreaRun {
  std::vector<PlannedArea> areas;                // targets' `material` still unresolved (0)
  std::vector<std::vector<std::string>> splats;  // per area, per target: its splat material
  std::vector<AreaClassReport> reports;
};

// What the methods before the areas keep them out of (SynthesisMethod::keep_out: the curve
// patterns' coverage), burnt over a canvas's lattice; empty: nothing.
using KeepOut = std::function<void(const GridSpec& lattice, SparseRaster<std::uint8_t>& forbidden)>;

// `heights` is read for lead: contours only.
// Throws tw::Error naming the class and FID when a stroke touches a forbidden pixel (a bug).
AreaRun synthesize_areas(const PipelineConfig& config,
                         const std::vector<std::vector<PolygonFeature>>& polygons,
                         const std::vector<std::vector<LineFeature>>& lines,
                         const FeatureRibbons& ribbons, const ExistingFeatures& existing,
                         const KeepOut& keep_out, HeightSampler& heights, Warnings& warnings);

}  // namespace tw::detail
