#include <memory>
#include <optional>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/detail/vector_layer.hpp"
#include "geo/features.hpp"

namespace tw {
namespace {

using detail::OpenVectorLayer;

// The polygon parts of a feature's geometry (curves linearized); tw::Error for anything else.
std::unique_ptr<OGRGeometry> polygon_parts(const OGRFeature& feature,
                                           const OpenVectorLayer& layer) {
  const std::int64_t fid = feature.GetFID();
  const std::unique_ptr<OGRGeometry> linear = detail::linear_geometry(feature, layer);
  const OGRwkbGeometryType type = wkbFlatten(linear->getGeometryType());
  auto parts = std::make_unique<OGRMultiPolygon>();
  if (type == wkbPolygon) {
    parts->addGeometry(linear.get());
  } else if (type == wkbMultiPolygon) {
    for (const OGRPolygon* part : *linear->toMultiPolygon()) parts->addGeometry(part);
  } else {
    fail("{}: FID {}: is a {} where polygons (Polygon/MultiPolygon) are expected", layer.label, fid,
         OGRGeometryTypeToName(type));
  }
  return parts;
}

void collect_polygons(const OGRGeometry& geometry, std::vector<const OGRPolygon*>& polygons) {
  const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbPolygon) {
    if (!geometry.IsEmpty()) polygons.push_back(geometry.toPolygon());
  } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *geometry.toGeometryCollection()) {
      collect_polygons(*part, polygons);
    }
  }
  // Lines and points (where a polygon only touches the border) cover no area: dropped.
}

// `parts` itself when valid; else GEOS's MakeValid of it (its polygons; lines and points that
// the repair splits off cover no area) with a `repaired` warning.
std::unique_ptr<OGRGeometry> valid_polygons(std::unique_ptr<OGRGeometry> parts,
                                            const OpenVectorLayer& layer, std::int64_t fid,
                                            const std::string& subject, Warnings& warnings) {
  detail::QuietGdalErrors quiet;
  if (parts->IsValid()) return parts;
  if (!OGRGeometryFactory::haveGEOS()) {
    fail("{}: FID {}: is not a valid polygon and GDAL was built without GEOS to repair it",
         layer.label, fid);
  }
  std::unique_ptr<OGRGeometry> valid(parts->MakeValid());
  if (!valid || !valid->IsValid()) {
    fail("{}: FID {}: is not a valid polygon and cannot be repaired: {}", layer.label, fid,
         detail::last_gdal_error());
  }
  std::vector<const OGRPolygon*> polygons;
  collect_polygons(*valid, polygons);
  auto multi = std::make_unique<OGRMultiPolygon>();
  for (const OGRPolygon* polygon : polygons) multi->addGeometry(polygon);
  warnings.add("repaired", subject, fid,
               fmt::format("{}: invalid polygon (self-intersecting or badly nested rings) made "
                           "valid: {} polygon{}",
                           layer.label, polygons.size(), polygons.size() == 1 ? "" : "s"));
  return multi;
}

// The polygons of `parts` (in the layer's CRS) near the grid: cut to `box` (GEOS), so that only
// what can land on the grid is transformed. An invalid polygon that GEOS cannot cut is made
// valid first (valid_polygons, with its warning).
std::unique_ptr<OGRGeometry> cut_to_box(std::unique_ptr<OGRGeometry> parts, const OGREnvelope& box,
                                        const OpenVectorLayer& layer, std::int64_t fid,
                                        const std::string& subject, Warnings& warnings) {
  OGREnvelope parts_box;
  parts->getEnvelope(&parts_box);
  if (box.Contains(parts_box)) return parts;
  if (!box.Intersects(parts_box)) return std::make_unique<OGRMultiPolygon>();
  const OGRPolygon box_polygon = detail::densified_box(box);
  std::unique_ptr<OGRGeometry> inside;
  {
    detail::QuietGdalErrors quiet;
    inside.reset(parts->Intersection(&box_polygon));
  }
  if (!inside) {
    parts = valid_polygons(std::move(parts), layer, fid, subject, warnings);
    detail::QuietGdalErrors quiet;
    inside.reset(parts->Intersection(&box_polygon));
    if (!inside) {
      fail("{}: FID {}: cannot clip to the grid: {}", layer.label, fid, detail::last_gdal_error());
    }
  }
  std::vector<const OGRPolygon*> polygons;
  collect_polygons(*inside, polygons);
  auto multi = std::make_unique<OGRMultiPolygon>();
  for (const OGRPolygon* polygon : polygons) multi->addGeometry(polygon);
  return multi;
}

std::vector<Vec2> open_ring(const OGRLinearRing& ring) {
  std::vector<Vec2> points = detail::distinct_points(ring);
  if (points.size() >= 2 && points.front() == points.back()) points.pop_back();
  return points;
}

}  // namespace

std::vector<PolygonFeature> read_polygon_features(const VectorSource& source,
                                                  const Heightfield& grid_of,
                                                  const std::string& subject, Warnings& warnings) {
  OpenVectorLayer layer = detail::open_vector_layer(source, grid_of);
  const OGRPolygon extent = detail::grid_extent_polygon(grid_of.grid);
  OGREnvelope extent_box;
  extent.getEnvelope(&extent_box);
  std::vector<PolygonFeature> result;
  layer.layer->ResetReading();
  while (const OGRFeatureUniquePtr feature = detail::next_feature(layer)) {
    const std::int64_t fid = feature->GetFID();
    std::unique_ptr<OGRGeometry> parts = polygon_parts(*feature, layer);
    if (detail::drop_z_and_m(*parts)) {
      warnings.add(
          "dropped_zm", subject, std::nullopt,
          fmt::format("{}: Z/M values dropped (heights come from the heightfield)", layer.label));
    }
    detail::check_coordinates(*parts, layer, fid);
    // Clip first, then judge: a polygon off the grid is skipped whatever its shape. Cut in the
    // layer's own CRS before transforming, so that a continent or a country reaching beyond the
    // grid CRS's domain (a UTM zone) transforms only where it is near the grid.
    if (layer.to_grid) {
      if (const std::optional<OGREnvelope> near = detail::grid_box_in_layer_crs(layer, 0.0))
        parts = cut_to_box(std::move(parts), *near, layer, fid, subject, warnings);
    }
    OGREnvelope box;
    std::vector<const OGRPolygon*> polygons;
    std::unique_ptr<OGRGeometry> inside;
    if (!parts->IsEmpty() && detail::transform_parts_to_grid(*parts->toGeometryCollection(), layer,
                                                             fid, subject, warnings)) {
      parts->getEnvelope(&box);
    }
    if (!parts->IsEmpty() && box.Intersects(extent_box)) {
      parts = valid_polygons(std::move(parts), layer, fid, subject, warnings);
      detail::QuietGdalErrors quiet;
      inside.reset(parts->Intersection(&extent));
      if (!inside) {
        fail("{}: FID {}: cannot clip to the grid: {}", layer.label, fid,
             detail::last_gdal_error());
      }
      collect_polygons(*inside, polygons);
    }
    if (polygons.empty()) {
      logger().info("{}: FID {} lies outside the grid; skipped", layer.label, fid);
    }
    for (const OGRPolygon* polygon : polygons) {
      PolygonFeature clipped{fid, {}, layer.label};
      for (const OGRLinearRing* ring : *polygon) clipped.rings.push_back(open_ring(*ring));
      result.push_back(std::move(clipped));
    }
  }
  return result;
}

}  // namespace tw
