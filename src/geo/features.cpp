#include "geo/features.hpp"

#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/detail/line_clipping.hpp"
#include "geo/detail/line_repair.hpp"
#include "geo/detail/vector_layer.hpp"
#include "geo/osm_tags.hpp"

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

// The columns a feature's width, structure and layer are read from; -1 where absent.
struct AttributeColumns {
  int width_attribute = -1;
  int osm_width = -1, lanes = -1, highway = -1, waterway = -1, natural = -1;
  int bridge = -1, tunnel = -1, layer = -1;
};

AttributeColumns attribute_columns(const LineClassSpec& spec, const OpenVectorLayer& layer) {
  const OGRFeatureDefn& definition = *layer.layer->GetLayerDefn();
  auto column = [&](const char* name) { return definition.GetFieldIndex(name); };
  AttributeColumns c;
  c.width_attribute = width_field_index(spec, layer);
  if (spec.osm_widths) {
    c.osm_width = column("width");
    c.lanes = column("lanes");
    c.highway = column("highway");
    c.waterway = column("waterway");
    c.natural = column("natural");
  }
  c.bridge = column("bridge");
  c.tunnel = column("tunnel");
  c.layer = column("layer");
  return c;
}

std::string text_of(const OGRFeature& feature, int column) {
  return column >= 0 && feature.IsFieldSetAndNotNull(column) ? feature.GetFieldAsString(column)
                                                             : "";
}

double feature_width(const OGRFeature& feature, const AttributeColumns& columns,
                     const LineClassSpec& spec, const OpenVectorLayer& layer, Warnings& warnings) {
  const int width_field = columns.width_attribute;
  const bool from_attribute = width_field >= 0 && feature.IsFieldSetAndNotNull(width_field);
  double width = from_attribute ? feature.GetFieldAsDouble(width_field) : spec.default_width;
  std::string from = from_attribute ? fmt::format("attribute '{}'", spec.width_attribute)
                                    : fmt::format("the default width of class '{}'", spec.name);
  if (!from_attribute && spec.osm_widths) {
    const OsmWidth tagged =
        osm_width({text_of(feature, columns.osm_width), text_of(feature, columns.lanes),
                   text_of(feature, columns.highway), text_of(feature, columns.waterway),
                   text_of(feature, columns.natural)});
    if (!tagged.problem.empty()) {
      warnings.add("osm_tag", "features." + spec.name, feature.GetFID(),
                   fmt::format("{}: {}; width from {}", layer.label, tagged.problem,
                               tagged.metres ? tagged.from : "the class default"));
    }
    if (tagged.metres) {
      width = *tagged.metres;
      from = "the OSM tag " + tagged.from;
    } else if (spec.default_width <= 0.0) {
      from = fmt::format(
          "the OSM tag table (no width, lanes or known class) and class '{}' "
          "has no default width",
          spec.name);
    }
  }
  if (!(std::isfinite(width) && width > 0.0)) {
    fail("{}: FID {}: width must be a positive number of metres, got {} (from {})", layer.label,
         feature.GetFID(), width, from);
  }
  if (width > kMaxFeatureWidth) {
    fail("{}: FID {}: width {:g} m is over the limit of {:g} m (from {})", layer.label,
         feature.GetFID(), width, kMaxFeatureWidth, from);
  }
  return width;
}

// bridge / tunnel / layer; a malformed layer is read as 0 with a warning.
void read_structure(const OGRFeature& feature, const AttributeColumns& columns,
                    const LineClassSpec& spec, const OpenVectorLayer& layer, Warnings& warnings,
                    Structure& structure, int& level) {
  structure = osm_structure(text_of(feature, columns.bridge), text_of(feature, columns.tunnel));
  level = 0;
  const std::string text = text_of(feature, columns.layer);
  if (text.empty()) return;
  if (const auto parsed = parse_osm_layer(text)) {
    level = *parsed;
  } else {
    warnings.add(
        "osm_tag", "features." + spec.name, feature.GetFID(),
        fmt::format("{}: layer={} is not a whole number; read as layer 0", layer.label, text));
  }
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

std::string warning_subject(const LineClassSpec& spec) {
  return spec.subject.empty() ? spec.name : spec.subject;
}

// Repairs one piece in place, through spec.repair_memo where there is one; adds what it
// changed to `counts`. Returns false when the piece is to be dropped.
bool repair_piece(detail::ClippedLine& piece, const LineClassSpec& spec, LineRepairCounts& counts) {
  if (!spec.repair_memo)
    return detail::repair_line(piece.points, piece.closed, spec.repair, counts);
  const ContentHash key = line_repair_key(piece.points, piece.closed, spec.repair);
  std::optional<RepairedPiece> repaired = spec.repair_memo.lookup(key);
  if (!repaired) {
    repaired.emplace();
    repaired->points = piece.points;
    // A dropped piece is stored as no points: repair_line empties them when it returns false.
    detail::repair_line(repaired->points, piece.closed, spec.repair, repaired->counts);
    spec.repair_memo.store(key, *repaired);
  }
  piece.points = std::move(repaired->points);
  counts.add(repaired->counts);
  return !piece.points.empty();
}

// Judges the clipped pieces of one feature: repairs each, drops those left without length,
// and says once what changed.
void repair_pieces(std::vector<detail::ClippedLine>& pieces, const LineClassSpec& spec,
                   const OpenVectorLayer& layer, std::int64_t fid, Warnings& warnings) {
  LineRepairCounts counts;
  try {
    std::erase_if(pieces,
                  [&](detail::ClippedLine& piece) { return !repair_piece(piece, spec, counts); });
  } catch (const Error& e) {
    fail("{}: FID {}: {}", layer.label, fid, e.what());
  }
  if (counts.changed()) {
    warnings.add("repaired", warning_subject(spec), fid,
                 fmt::format("{}: {}", layer.label, detail::describe(counts)));
  }
  if (counts.self_crossings > 0) {
    logger().info("{}: FID {} crosses itself at {} place{}: a junction", layer.label, fid,
                  counts.self_crossings, counts.self_crossings == 1 ? "" : "s");
  }
}

}  // namespace

std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of) {
  Warnings logged_only;  // Warnings::add logs each one
  return read_line_features(spec, grid_of, logged_only);
}

std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of,
                                            Warnings& warnings) {
  OpenVectorLayer layer = detail::open_vector_layer(spec.source, grid_of);
  const AttributeColumns columns = attribute_columns(spec, layer);
  std::vector<LineFeature> lines;
  layer.layer->ResetReading();
  while (const OGRFeatureUniquePtr feature = detail::next_feature(layer)) {
    const std::int64_t fid = feature->GetFID();
    const double width = feature_width(*feature, columns, spec, layer, warnings);
    Structure structure = Structure::ground;
    int level = 0;
    read_structure(*feature, columns, spec, layer, warnings, structure, level);
    std::unique_ptr<OGRMultiLineString> parts = line_parts(*feature, layer);
    if (detail::drop_z_and_m(*parts)) {
      warnings.add(
          "dropped_zm", warning_subject(spec), std::nullopt,
          fmt::format("{}: Z/M values dropped (heights come from the heightfield)", layer.label));
    }
    detail::check_coordinates(*parts, layer, fid);
    // Clip first, then judge: nothing outside the world (and its halo) can fail a run. Cut in
    // the layer's own CRS before transforming, so that a country border or coastline reaching
    // beyond the grid CRS's domain (a UTM zone) transforms only where it is near the grid.
    const double margin = 0.5 * width + spec.clip_margin;
    if (layer.to_grid) {
      if (const std::optional<OGREnvelope> box = detail::grid_box_in_layer_crs(layer, margin))
        parts = detail::cut_to_box(*parts, *box, layer, fid);
    }
    std::vector<detail::ClippedLine> pieces;
    if (!parts->IsEmpty() &&
        detail::transform_parts_to_grid(*parts, layer, fid, warning_subject(spec), warnings)) {
      const OGRPolygon extent = detail::grid_extent_polygon(grid_of.grid, margin);
      for (const OGRLineString* part : *parts) {
        for (detail::ClippedLine& piece : detail::clip_line(*part, extent, layer, fid)) {
          pieces.push_back(std::move(piece));
        }
      }
    }
    if (pieces.empty()) {
      logger().info("{}: FID {} lies outside the grid; skipped", layer.label, fid);
      continue;
    }
    repair_pieces(pieces, spec, layer, fid, warnings);
    for (detail::ClippedLine& piece : pieces) {
      lines.push_back(
          {fid, std::move(piece.points), piece.closed, width, layer.label, structure, level});
    }
  }
  return lines;
}

std::optional<std::string> why_no_features(const VectorSource& source, const Heightfield& grid_of) {
  OpenVectorLayer layer = detail::open_vector_layer(source, grid_of);
  return detail::why_no_features(layer, source.where);
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
  // As the pipeline: a zero-length line is refused; one crossing itself is drawn as it is.
  if (detail::distinct_points(line).size() < 2) {
    fail("{}: FID {}: part 0 has zero length", layer.label, fid);
  }
  LineFeature result{fid, detail::distinct_points(line), false, 0.0, layer.label};
  if (result.points.size() > 2 && result.points.front() == result.points.back()) {
    result.points.pop_back();
    result.closed = true;
  }
  return result;
}

}  // namespace tw
