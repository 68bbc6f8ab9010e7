#include "commands/detail/vector_inputs.hpp"

#include "core/error.hpp"

namespace tw::detail {

VectorSource vector_source(const std::string& source, const std::string& where) {
  VectorSource vector;
  vector.path = source;
  vector.where = where;
  if (const auto colon = source.rfind(':'); colon != std::string::npos && colon > 1) {
    vector.path = source.substr(0, colon);
    vector.layer = source.substr(colon + 1);
  }
  return vector;
}

OpenLayer open_layer(const VectorSource& source) {
  GDALAllRegister();
  OpenLayer out;
  out.dataset.reset(GDALDataset::Open(source.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                      nullptr, nullptr, nullptr));
  if (!out.dataset) fail("{}: cannot open as vector data", source.path);
  out.layer = source.layer.empty() ? out.dataset->GetLayer(0)
                                   : out.dataset->GetLayerByName(source.layer.c_str());
  if (!out.layer) fail("{}: no layer '{}'", source.path, source.layer);
  return out;
}

bool is_polygon_layer(const VectorSource& source) {
  const OpenLayer opened = open_layer(source);
  const auto type = wkbFlatten(opened.layer->GetGeomType());
  return type == wkbPolygon || type == wkbMultiPolygon;
}

namespace {

bool has_field(const VectorSource& source, const char* name) {
  return open_layer(source).layer->GetLayerDefn()->GetFieldIndex(name) >= 0;
}

}  // namespace

AvoidanceInputs avoided_features(const Heightfield& frame, const std::vector<std::string>& avoid,
                                 double default_width, const std::string& subject,
                                 Warnings& warnings) {
  AvoidanceInputs inputs;
  for (const std::string& path : avoid) {
    const VectorSource source = vector_source(path, "");
    if (is_polygon_layer(source)) {
      for (PolygonFeature& f : read_polygon_features(source, frame, subject, warnings)) {
        inputs.polygons.emplace_back(f.rings.begin(), f.rings.end());
      }
      continue;
    }
    LineClassSpec spec;
    spec.name = "avoid";
    spec.source = source;
    // Lines without a `width` column take the default width (or their OSM tags').
    if (has_field(source, "width")) spec.width_attribute = "width";
    spec.default_width = default_width;
    spec.osm_widths = true;
    spec.subject = subject;
    for (LineFeature& line : read_line_features(spec, frame, warnings)) {
      inputs.lines.push_back(std::move(line.points));
      inputs.line_widths.push_back(line.width);
    }
  }
  return inputs;
}

}  // namespace tw::detail
