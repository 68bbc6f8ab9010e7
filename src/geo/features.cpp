#include "geo/features.hpp"

#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/detail/line_clipping.hpp"
#include "geo/detail/vector_layer.hpp"

namespace tw {
namespace {

using detail::OpenVectorLayer;

int width_field_index(const LineClassSpec& spec, const OpenVectorLayer& layer) {
  if (spec.width_attribute.empty()) return -1;
  const int index = layer.layer->GetLayerDefn()->GetFieldIndex(spec.width_attribute.c_str());
  if (index < 0) {
    fail("{}: no attribute '{}' to read widths from (class '{}')", layer.label,
         spec.width_attribute, spec.name);
  }
  return index;
}

double feature_width(const OGRFeature& feature, int width_field, const LineClassSpec& spec,
                     const OpenVectorLayer& layer) {
  const bool from_attribute = width_field >= 0 && feature.IsFieldSetAndNotNull(width_field);
  const double width = from_attribute ? feature.GetFieldAsDouble(width_field) : spec.default_width;
  const std::string origin = from_attribute
                                 ? fmt::format("attribute '{}'", spec.width_attribute)
                                 : fmt::format("the default width of class '{}'", spec.name);
  if (!(std::isfinite(width) && width > 0.0)) {
    fail("{}: FID {}: width must be a positive number of metres, got {} (from {})", layer.label,
         feature.GetFID(), width, origin);
  }
  if (width > kMaxFeatureWidth) {
    fail("{}: FID {}: width {:g} m is over the limit of {:g} m (from {})", layer.label,
         feature.GetFID(), width, kMaxFeatureWidth, origin);
  }
  return width;
}

// The line parts of a feature's geometry (curves linearized); tw::Error for anything else.
std::unique_ptr<OGRMultiLineString> line_parts(const OGRFeature& feature,
                                               const OpenVectorLayer& layer) {
  const std::int64_t fid = feature.GetFID();
  const std::unique_ptr<OGRGeometry> linear = detail::linear_geometry(feature, layer);
  const OGRwkbGeometryType type = wkbFlatten(linear->getGeometryType());
  auto parts = std::make_unique<OGRMultiLineString>();
  if (type == wkbLineString) {
    parts->addGeometry(linear.get());
  } else if (type == wkbMultiLineString) {
    for (const OGRLineString* part : *linear->toMultiLineString()) parts->addGeometry(part);
  } else {
    fail("{}: FID {}: is a {} where lines (LineString/MultiLineString) are expected", layer.label,
         fid, OGRGeometryTypeToName(type));
  }
  return parts;
}

void check_line_part(const OGRLineString& part, int part_index, const OpenVectorLayer& layer,
                     std::int64_t fid) {
  if (detail::distinct_points(part).size() < 2) {
    fail("{}: FID {}: part {} has zero length", layer.label, fid, part_index);
  }
  detail::QuietGdalErrors quiet;
  if (!part.IsSimple()) {
    fail("{}: FID {}: part {} intersects itself", layer.label, fid, part_index);
  }
}

}  // namespace

std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of) {
  OpenVectorLayer layer = detail::open_vector_layer(spec.source, grid_of);
  const int width_field = width_field_index(spec, layer);
  const OGRPolygon extent = detail::grid_extent_polygon(grid_of.grid);
  std::vector<LineFeature> lines;
  for (const auto& feature : *layer.layer) {
    const std::int64_t fid = feature->GetFID();
    const double width = feature_width(*feature, width_field, spec, layer);
    std::unique_ptr<OGRMultiLineString> parts = line_parts(*feature, layer);
    detail::check_coordinates(*parts, layer, fid);
    for (int i = 0; i < parts->getNumGeometries(); ++i) {
      check_line_part(*parts->getGeometryRef(i), i, layer, fid);
    }
    detail::transform_to_grid(*parts, layer, fid);
    const std::size_t before = lines.size();
    for (const OGRLineString* part : *parts) {
      for (detail::ClippedLine& piece : detail::clip_line(*part, extent, layer, fid)) {
        lines.push_back({fid, std::move(piece.points), piece.closed, width, layer.label});
      }
    }
    if (lines.size() == before) {
      logger().info("{}: FID {} lies outside the grid; skipped", layer.label, fid);
    }
  }
  return lines;
}

LineFeature read_first_line_feature(const VectorSource& source) {
  const OpenVectorLayer layer = detail::open_vector_layer(source);
  const OGRSpatialReference* srs = layer.layer->GetSpatialRef();
  if (!srs->IsProjected() || std::abs(srs->GetLinearUnits() - 1.0) > 1e-12)
    fail("{}: needs a projected CRS in metres", layer.label);
  layer.layer->ResetReading();
  const OGRFeatureUniquePtr feature(layer.layer->GetNextFeature());
  if (!feature) fail("{}: empty layer", layer.label);
  const std::int64_t fid = feature->GetFID();
  const std::unique_ptr<OGRMultiLineString> parts = line_parts(*feature, layer);
  detail::check_coordinates(*parts, layer, fid);
  const OGRLineString& line = *parts->getGeometryRef(0);
  check_line_part(line, 0, layer, fid);
  LineFeature result{fid, detail::distinct_points(line), false, 0.0, layer.label};
  if (result.points.size() > 2 && result.points.front() == result.points.back()) {
    result.points.pop_back();
    result.closed = true;
  }
  return result;
}

}  // namespace tw
