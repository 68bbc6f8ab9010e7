#include "geo/features.hpp"

#include "core/error.hpp"

namespace tw {

std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield&) {
  fail("{}: read_line_features is not implemented yet", spec.source.path);
}

std::vector<PolygonFeature> read_polygon_features(const VectorSource& source, const Heightfield&) {
  fail("{}: read_polygon_features is not implemented yet", source.path);
}

}  // namespace tw
