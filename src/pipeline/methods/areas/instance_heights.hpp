#pragma once
// The z of the areas' engine instances (docs/shape-patterns.md, "Outputs"): the final height
// layer's pixel under each instance, after grading, carving and the areas' own height detail.
// The height is a per-pixel function of the world grid, so each tile gives the instances whose
// pixel lies in its core window, and any tiling (or a render-tile worker's tile result, or a
// tile reused from the cache) gives the same z.
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "pipeline/methods/areas/area_method.hpp"

namespace tw::detail {

// Per area of the plan's areas entry, per instance: its z, NaN where no tile held its pixel (beyond
// the output window or the grid).
using InstanceHeights = std::vector<std::vector<double>>;

// The instances whose pixel lies in `core`, with the height there, as a tile fact (text: one
// "area instance float-bits" line each). `height` covers `halo` of `grid`, the plan's.
std::string instance_heights_fact(const GridSpec& grid, const AreasPlan& areas,
                                  const Raster<float>& height, const Window& halo,
                                  const Window& core);

// Every instance unknown (NaN).
InstanceHeights unknown_instance_heights(const AreasPlan& areas);

// The heights of one tile's fact into `heights`. Throws tw::Error naming `where` when the fact
// is not one instance_heights_fact wrote for this plan.
void add_instance_heights(const std::string& fact, const std::string& where,
                          InstanceHeights& heights);

}  // namespace tw::detail
