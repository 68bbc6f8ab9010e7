#pragma once
// The pipeline's side of conformance (docs/terrain.md, "Conformance"): lines moved onto the
// DEM right after ingest, so ribbons, synthesis and terrain all use the conformed line; and
// the earthwork each feature needed, in the report and as warnings where a bound held.
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/run.hpp"
#include "terrain/height_ops.hpp"

namespace tw::detail {

// How far each line was moved, per class (config order) and feature (reading order).
struct LineMove {
  double max_m = 0.0;
  double mean_m = 0.0;
};

// Moves the lines of every class with a conform.corridor onto the valley floor (rivers) or
// the crest (ridges) of `heightfield`; a moved line is a `conformed` warning, one that could
// not be moved a `not_conformed` warning. Reads the cells of the corridors only.
std::vector<std::vector<LineMove>> conform_lines(const TerrainOptions& terrain,
                                                 const HeightfieldSource& heightfield,
                                                 std::vector<std::vector<LineFeature>>& lines,
                                                 Warnings& warnings);

// Copies each feature's largest cut and fill from `plan` (built from terrain_features(terrain,
// lines)) into report.classes, and warns where a bound held it: `carve_limited` (a river's
// max_carve), `cut_limited` / `fill_limited` (a road's max_cut / max_fill).
void report_earthwork(const TerrainOptions& terrain,
                      const std::vector<std::vector<LineFeature>>& lines, const TerrainPlan& plan,
                      RunReport& report, Warnings& warnings);

}  // namespace tw::detail
