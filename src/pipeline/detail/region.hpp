#pragma once
// A run's `region` (config.hpp) as a window of the world's grid: the run plans the world's
// features, synthesizes those that reach the region, and renders the region's pixels only, so
// its layers are the same bytes as the same window of a run without the region.
#include <string>

#include "core/grid.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

// The pixels of `grid` whose cells meet the region (min_x, min_y, max_x, max_y in the grid's
// CRS). Throws tw::Error naming `region` and `source` when it does not overlap the grid.
Window region_window(const GridSpec& grid, const RegionConfig& region, const std::string& source);

}  // namespace tw::detail
