#pragma once
// The network module's polygons as OGR geometry, for GEOS's predicates and cuts.
#include <ogr_geometry.h>

#include <vector>

#include "raster/polygon.hpp"

namespace tw::detail {

// Every polygon with its holes, rings closed.
OGRMultiPolygon to_ogr(const std::vector<Polygon>& polygons);

}  // namespace tw::detail
