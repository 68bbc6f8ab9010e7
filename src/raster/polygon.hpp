#pragma once
// Polygons in world metres, as rasterized by this module (same layout as geo's feature rings).
#include <vector>

#include "core/vec2.hpp"

namespace tw {

// A closed ring; the closing edge back to the first point is implicit (a repeated first point is
// harmless).
using Ring = std::vector<Vec2>;
// [0] is the outer ring, the rest are holes. Filled with the even-odd rule over all its rings,
// like GDAL, so ring orientation does not matter.
using Polygon = std::vector<Ring>;

}  // namespace tw
