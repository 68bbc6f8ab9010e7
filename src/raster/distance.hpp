#pragma once
// Exact Euclidean distance transform (Felzenszwalb & Huttenlocher 2012, separable lower
// envelope of parabolas), in metres on pixels that may be non-square.
#include <cstdint>

#include "core/grid.hpp"

namespace tw {

// For each pixel, the distance in metres from its centre to the nearest centre of a non-zero
// pixel of `mask` (0 on those pixels). +infinity everywhere when the mask has no non-zero pixel.
// On a window the distance only sees the window: give it a halo at least as wide as the largest
// distance you care about. Parallel (TBB), deterministic. Throws tw::Error on pixel sizes <= 0.
Raster<float> distance_to_mask(const Raster<std::uint8_t>& mask, double pixel_w, double pixel_h);

}  // namespace tw
