#pragma once
// geo's features as avoidance inputs: polygons as they are, lines buffered by their widths.
#include <vector>

#include "geo/features.hpp"
#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"

namespace tw {

// The features' rings as polygons (index i is features[i]). Throws tw::Error naming the source
// and FID of a feature with no ring, a ring of fewer than 3 points or a non-finite point.
std::vector<Polygon> to_polygons(const std::vector<PolygonFeature>& features);

// Appends the features to inputs.polygons / inputs.lines + inputs.line_widths (closed lines get
// their closing segment). Throws tw::Error naming source and FID for a width < 0 or a non-finite
// point.
void add_features(const std::vector<PolygonFeature>& polygons,
                  const std::vector<LineFeature>& lines, AvoidanceInputs& inputs);

}  // namespace tw
