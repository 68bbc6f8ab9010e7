#pragma once
// The output grid of a run with a `region` (config.hpp): the heightfield cropped to the region
// and resampled to the run's resolution.
#include "geo/heightfield.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

// The region's cells at `resolution` metres, their edges on multiples of it in world
// coordinates (so every close-up of a run lies on one lattice), heights read from the valid
// cells of `source` with geo/resample.hpp (NaN over nodata cells). Throws tw::Error naming
// `region` when it does not overlap the heightfield.
Heightfield crop_to_region(const Heightfield& source, const RegionConfig& region, double resolution,
                           Resampling resampling = Resampling::bilinear);

}  // namespace tw::detail
