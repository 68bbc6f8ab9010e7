#pragma once
// The per-pixel ribbon frame of a centerline: for each pixel centre within `reach` metres,
// the nearest point of the curve as (arc length along, signed distance across). Positive
// across is the left of the direction of travel (the ribbon's "top", see ribbon/ribbon.hpp).
#include <limits>

#include "core/grid.hpp"
#include "ribbon/curve.hpp"

namespace tw {

struct RibbonFrame {
  Window window;         // the pixels of the grid this frame covers
  Raster<float> along;   // metres of arc length from the first point; NaN beyond reach
  Raster<float> across;  // signed metres; NaN beyond reach
};

// Exact nearest-point frame over `window`, scanning each segment's reach-expanded bounding
// box (work proportional to the pixels near the curve). Deterministic: ties go to the
// earlier segment.
RibbonFrame compute_ribbon_frame(const GridSpec& grid, const Window& window, const Curve& curve,
                                 double reach);

}  // namespace tw
