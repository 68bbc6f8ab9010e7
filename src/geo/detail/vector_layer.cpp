#include "geo/detail/vector_layer.hpp"

#include <cmath>
#include <optional>

#include <cpl_conv.h>

#include "core/error.hpp"
#include "geo/detail/osm_config.hpp"
#include "geo/input_guard.hpp"

namespace tw::detail {
namespace {

std::string layer_names(GDALDataset& dataset) {
  std::string names;
  for (OGRLayer* layer : dataset.GetLayers()) {
    names += names.empty() ? "" : ", ";
    names += layer->GetName();
  }
  return names.empty() ? "none" : names;
}

// Some drivers (GeoPackage) accept any filter and only fail when reading: read one feature
// to find out while we can still name the clause.
void apply_where(OGRLayer& layer, const std::string& where, const std::string& label) {
  CPLErrorReset();
  const OGRErr set = layer.SetAttributeFilter(where.c_str());
  bool failed = set != OGRERR_NONE || CPLGetLastErrorType() >= CE_Failure;
  if (!failed) {
    layer.ResetReading();
    OGRFeatureUniquePtr probe(layer.GetNextFeature());
    failed = CPLGetLastErrorType() >= CE_Failure;
    layer.ResetReading();
  }
  if (!failed) return;
  const std::string error = last_gdal_error();
  // A layer that cannot be read at all fails with any clause: say so, not "bad where clause".
  CPLErrorReset();
  layer.SetAttributeFilter(nullptr);
  layer.ResetReading();
  OGRFeatureUniquePtr unfiltered(layer.GetNextFeature());
  const bool unreadable = CPLGetLastErrorType() >= CE_Failure;
  layer.ResetReading();
  if (unreadable) fail("{}: reading its features failed: {}", label, last_gdal_error());
  fail("{}: bad where clause '{}': {}", label, where, error);
}

}  // namespace

OpenVectorLayer open_vector_layer(const VectorSource& source) {
  ensure_gdal_registered();
  QuietGdalErrors quiet;
  OpenVectorLayer result;
  check_input_path(source.path, "vector source", network_access_allowed());
  {
    // OSM files get our osmconf.ini (its tags as columns) unless the user set their own.
    std::optional<CPLConfigOptionSetter> osm_config;
    if (!CPLGetConfigOption("OSM_CONFIG_FILE", nullptr)) {
      osm_config.emplace("OSM_CONFIG_FILE", osm_config_file().c_str(),
                         /*bSetOnlyIfUndefined=*/true);
    }
    // GDAL's own node index takes only positive ids in increasing order: files saved by an
    // editor (JOSM: negative ids of new objects, nodes in any order) read as nothing. Its
    // SQLite index takes every file (spilling to a temporary file past OSM_MAX_TMPFILE_SIZE).
    const CPLConfigOptionSetter osm_index("OSM_USE_CUSTOM_INDEXING", "NO",
                                          /*bSetOnlyIfUndefined=*/true);
    result.dataset.reset(GDALDataset::Open(source.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  }
  if (!result.dataset) {
    fail("{}: cannot open as vector data: {}", source.path, open_failure(source.path));
  }
  if (source.layer.empty()) {
    if (result.dataset->GetLayerCount() < 1) fail("{}: has no vector layer", source.path);
    result.layer = result.dataset->GetLayer(0);
  } else {
    result.layer = result.dataset->GetLayerByName(source.layer.c_str());
    if (!result.layer) {
      fail("{}: no layer '{}' (layers: {})", source.path, source.layer,
           layer_names(*result.dataset));
    }
  }
  result.label = fmt::format("{}:{}", source.path, result.layer->GetName());
  if (!source.where.empty()) apply_where(*result.layer, source.where, result.label);

  const OGRSpatialReference* layer_srs = result.layer->GetSpatialRef();
  if (!layer_srs || layer_srs->IsEmpty()) {
    fail("{}: layer has no CRS; cannot place its features on the grid", result.label);
  }
  OGRSpatialReference from(*layer_srs);
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  result.source_is_geographic = from.IsGeographic();
  result.crs_name = from.GetName() ? from.GetName() : "unnamed";
  result.is_geojson = std::string_view(result.dataset->GetDriverName()) == "GeoJSON";
  return result;
}

OpenVectorLayer open_vector_layer(const VectorSource& source, const Heightfield& grid_of) {
  OpenVectorLayer result = open_vector_layer(source);
  QuietGdalErrors quiet;
  OGRSpatialReference from(*result.layer->GetSpatialRef());
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference to;
  if (!import_traditional_srs(to, grid_of.crs_wkt)) {
    fail("{}: the heightfield '{}' has no usable CRS", result.label, grid_of.source);
  }
  if (!from.IsSame(&to)) {
    result.to_grid.reset(OGRCreateCoordinateTransformation(&from, &to));
    if (!result.to_grid) {
      fail("{}: no transformation from the layer's CRS to the grid's: {}", result.label,
           last_gdal_error());
    }
    result.to_layer.reset(OGRCreateCoordinateTransformation(&to, &from));
  }
  result.grid = grid_of.grid;
  return result;
}

OGRPolygon grid_extent_polygon(const GridSpec& grid, double margin) {
  const double west = grid.origin_x - margin;
  const double north = grid.origin_y + margin;
  const double east = grid.origin_x + grid.width * grid.pixel_width + margin;
  const double south = grid.origin_y - grid.height * grid.pixel_height - margin;
  OGRLinearRing ring;
  ring.addPoint(west, south);
  ring.addPoint(east, south);
  ring.addPoint(east, north);
  ring.addPoint(west, north);
  ring.closeRings();
  OGRPolygon polygon;
  polygon.addRing(&ring);
  return polygon;
}

std::optional<OGREnvelope> grid_box_in_layer_crs(OpenVectorLayer& layer, double margin) {
  const auto cached = layer.grid_boxes.find(margin);
  if (cached != layer.grid_boxes.end()) return cached->second;
  std::optional<OGREnvelope>& box = layer.grid_boxes[margin];
  OGREnvelope extent;
  grid_extent_polygon(*layer.grid, margin).getEnvelope(&extent);
  if (!layer.to_grid) {
    box = extent;
    return box;
  }
  if (!layer.to_layer) return box;
  QuietGdalErrors quiet;
  OGREnvelope out;
  constexpr int kSamplesPerEdge = 64;
  const bool ok =
      layer.to_layer->TransformBounds(extent.MinX, extent.MinY, extent.MaxX, extent.MaxY, &out.MinX,
                                      &out.MinY, &out.MaxX, &out.MaxY, kSamplesPerEdge) == TRUE;
  // An antimeridian crossing comes back as MinX > MaxX: no single box, no cut.
  if (!ok || !(out.MinX < out.MaxX && out.MinY < out.MaxY) || !std::isfinite(out.MinX) ||
      !std::isfinite(out.MaxX) || !std::isfinite(out.MinY) || !std::isfinite(out.MaxY)) {
    return box;
  }
  const double slack_x = 0.1 * (out.MaxX - out.MinX);
  const double slack_y = 0.1 * (out.MaxY - out.MinY);
  out.MinX -= slack_x;
  out.MaxX += slack_x;
  out.MinY -= slack_y;
  out.MaxY += slack_y;
  if (layer.source_is_geographic) {  // latitudes end at the poles
    out.MinY = std::max(out.MinY, -90.0);
    out.MaxY = std::min(out.MaxY, 90.0);
  }
  box = out;
  return box;
}

OGRPolygon densified_box(const OGREnvelope& box) {
  constexpr int kSegments = 64;
  OGRLinearRing ring;
  const std::pair<double, double> corners[] = {{box.MinX, box.MinY},
                                               {box.MaxX, box.MinY},
                                               {box.MaxX, box.MaxY},
                                               {box.MinX, box.MaxY},
                                               {box.MinX, box.MinY}};
  for (int edge = 0; edge < 4; ++edge) {
    const auto [x0, y0] = corners[edge];
    const auto [x1, y1] = corners[edge + 1];
    for (int i = 0; i < kSegments; ++i) {
      const double t = double(i) / kSegments;
      ring.addPoint(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
    }
  }
  ring.closeRings();
  OGRPolygon polygon;
  polygon.addRing(&ring);
  return polygon;
}

namespace {

// `reprojected`: the curve is in the grid's CRS after transform_parts_to_grid; an implausible
// vertex there means the layer's CRS does not describe its coordinates (or PROJ does not know it).
void check_curve(const OGRSimpleCurve& curve, bool geographic, bool reprojected,
                 const OpenVectorLayer& layer, std::int64_t fid) {
  for (int i = 0; i < curve.getNumPoints(); ++i) {
    const double x = curve.getX(i);
    const double y = curve.getY(i);
    const bool finite = std::isfinite(x) && std::isfinite(y);
    const bool plausible = geographic ? std::abs(x) <= 540.0 && std::abs(y) <= 90.0
                                      : std::abs(x) < 1e9 && std::abs(y) < 1e9;
    if (finite && !plausible && geographic) {
      fail(
          "{}: FID {}: vertex {} ({}, {}) is no longitude/latitude, yet the layer's CRS ({}) is "
          "geographic: is the CRS right?{}",
          layer.label, fid, i, x, y, layer.crs_name,
          layer.is_geojson ? " (GeoJSON reads a CRS that PROJ does not know as WGS 84)" : "");
    }
    if ((!finite || !plausible) && reprojected) {
      fail(
          "{}: FID {}: vertex {} lands at ({}, {}) in the grid's CRS: the layer's CRS ({}) does "
          "not fit its coordinates or cannot be transformed to the grid's",
          layer.label, fid, i, x, y, layer.crs_name);
    }
    if (!finite || !plausible) {
      fail("{}: FID {}: vertex {} has a non-finite or out-of-range coordinate ({}, {})",
           layer.label, fid, i, x, y);
    }
  }
}

void check_geometry(const OGRGeometry& geometry, bool geographic, bool reprojected,
                    const OpenVectorLayer& layer, std::int64_t fid) {
  const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbLineString || type == wkbLinearRing) {
    check_curve(*geometry.toSimpleCurve(), geographic, reprojected, layer, fid);
  } else if (type == wkbPolygon) {
    for (const OGRLinearRing* ring : *geometry.toPolygon()) {
      check_curve(*ring, geographic, reprojected, layer, fid);
    }
  } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *geometry.toGeometryCollection()) {
      check_geometry(*part, geographic, reprojected, layer, fid);
    }
  }
}

}  // namespace

void check_coordinates(const OGRGeometry& geometry, const OpenVectorLayer& layer,
                       std::int64_t fid) {
  check_geometry(geometry, layer.source_is_geographic, false, layer, fid);
}

bool transform_parts_to_grid(OGRGeometryCollection& parts, const OpenVectorLayer& layer,
                             std::int64_t fid, const std::string& subject, Warnings& warnings) {
  if (!layer.to_grid) return !parts.IsEmpty();
  QuietGdalErrors quiet;
  for (int i = parts.getNumGeometries() - 1; i >= 0; --i) {
    CPLErrorReset();
    if (parts.getGeometryRef(i)->transform(layer.to_grid.get()) == OGRERR_NONE) continue;
    warnings.add("dropped_part", subject, fid,
                 fmt::format("{}: a part PROJ cannot move into the grid's CRS ({}) was dropped",
                             layer.label, last_gdal_error()));
    parts.removeGeometry(i);
  }
  check_geometry(parts, false, true, layer, fid);
  return !parts.IsEmpty();
}

OGRFeatureUniquePtr next_feature(const OpenVectorLayer& layer) {
  QuietGdalErrors quiet;
  CPLErrorReset();
  OGRFeatureUniquePtr feature(layer.layer->GetNextFeature());
  if (CPLGetLastErrorType() >= CE_Failure) {
    fail("{}: reading its features failed: {}", layer.label, last_gdal_error());
  }
  return feature;
}

namespace {

// Rows under the layer's current filter; counted one by one where the driver cannot (OSM).
GIntBig count_rows(OGRLayer& rows) {
  GIntBig count = rows.GetFeatureCount(TRUE);
  if (count >= 0) return count;
  count = 0;
  rows.ResetReading();
  while (OGRFeatureUniquePtr(rows.GetNextFeature())) ++count;
  rows.ResetReading();
  return count;
}

}  // namespace

std::optional<std::string> why_no_features(OpenVectorLayer& layer, const std::string& where) {
  QuietGdalErrors quiet;
  OGRLayer& rows = *layer.layer;
  const GIntBig selected = count_rows(rows);
  rows.SetAttributeFilter(nullptr);
  const GIntBig all = count_rows(rows);
  OGREnvelope extent;
  const bool has_extent = rows.GetExtent(&extent, TRUE) == OGRERR_NONE;
  rows.SetAttributeFilter(where.empty() ? nullptr : where.c_str());
  rows.ResetReading();
  const std::optional<OGREnvelope> box = grid_box_in_layer_crs(layer, 0.0);
  if (all > 0 && has_extent && box && !extent.Intersects(*box)) return std::nullopt;
  if (all == 0) return fmt::format("{}: the layer has no rows", layer.label);
  if (selected == 0) {
    return fmt::format("{}: the where clause '{}' matches none of its {} rows", layer.label, where,
                       all);
  }
  return fmt::format(
      "{}: none of its {} feature{} lies on the heightfield, though the layer's extent meets it",
      layer.label, selected, selected == 1 ? "" : "s");
}

std::vector<Vec2> curve_points(const OGRSimpleCurve& curve) {
  std::vector<Vec2> points(std::size_t(curve.getNumPoints()));
  for (int i = 0; i < curve.getNumPoints(); ++i)
    points[std::size_t(i)] = {curve.getX(i), curve.getY(i)};
  return points;
}

bool drop_z_and_m(OGRGeometry& geometry) {
  const bool had = geometry.Is3D() || geometry.IsMeasured();
  if (had) {
    geometry.flattenTo2D();
    geometry.setMeasured(FALSE);
  }
  return had;
}

std::vector<Vec2> distinct_points(const OGRSimpleCurve& curve) {
  std::vector<Vec2> points;
  points.reserve(curve.getNumPoints());
  for (int i = 0; i < curve.getNumPoints(); ++i) {
    const Vec2 p{curve.getX(i), curve.getY(i)};
    if (points.empty() || points.back() != p) points.push_back(p);
  }
  return points;
}

std::unique_ptr<OGRGeometry> linear_geometry(const OGRFeature& feature,
                                             const OpenVectorLayer& layer) {
  const OGRGeometry* geometry = feature.GetGeometryRef();
  if (!geometry || geometry->IsEmpty())
    fail("{}: FID {}: has no geometry", layer.label, feature.GetFID());
  return std::unique_ptr<OGRGeometry>(geometry->hasCurveGeometry() ? geometry->getLinearGeometry()
                                                                   : geometry->clone());
}

}  // namespace tw::detail
