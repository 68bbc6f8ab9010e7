#include "sketch/sketch.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>

#include "core/error.hpp"

namespace tw {

namespace {

constexpr double kTolerance = 1e-6;

bool inside_input_space(Vec2 p) {
  return is_finite(p) && p.x >= -kTolerance && p.x <= 1.0 + kTolerance && p.y >= -kTolerance &&
         p.y <= 1.0 + kTolerance;
}

void check_stroke(const Stroke& stroke, const std::string& where) {
  if (stroke.points.size() < 2) fail("{}: a stroke needs two or more points", where);
  bool moves = false;
  for (Vec2 p : stroke.points) {
    if (!inside_input_space(p)) {
      fail("{}: point ({}, {}) lies outside the input space [0, 1] x [0, 1]", where, p.x, p.y);
    }
    moves = moves || distance(p, stroke.points.front()) > kTolerance;
  }
  if (!moves) fail("{}: all points of the stroke coincide", where);
  if (!(stroke.thickness > 0.0) || !std::isfinite(stroke.thickness)) {
    fail("{}: thickness must be > 0, got {}", where, stroke.thickness);
  }
}

Stroke stroke_from(const OGRLineString& line, const OGRFeature& feature, const std::string& where) {
  Stroke stroke;
  stroke.fid = feature.GetFID();
  for (int i = 0; i < line.getNumPoints(); ++i)
    stroke.points.push_back({line.getX(i), line.getY(i)});
  const int type_field = feature.GetFieldIndex("type");
  if (type_field >= 0 && feature.IsFieldSetAndNotNull(type_field)) {
    const std::string type = feature.GetFieldAsString(type_field);
    if (type != "bounded" && type != "unbounded") {
      fail("{}: type must be bounded or unbounded, got '{}'", where, type);
    }
    stroke.unbounded = type == "unbounded";
  }
  const int material_field = feature.GetFieldIndex("material");
  stroke.material = material_field >= 0 && feature.IsFieldSetAndNotNull(material_field)
                        ? feature.GetFieldAsString(material_field)
                        : "shape";
  const int thickness_field = feature.GetFieldIndex("thickness");
  if (thickness_field >= 0 && feature.IsFieldSetAndNotNull(thickness_field)) {
    // GetFieldAsDouble reads "abc" as 0: a text field must hold a whole number, nothing else.
    const OGRFieldType type = feature.GetFieldDefnRef(thickness_field)->GetType();
    if (type == OFTReal || type == OFTInteger || type == OFTInteger64) {
      stroke.thickness = feature.GetFieldAsDouble(thickness_field);
    } else {
      const std::string text = feature.GetFieldAsString(thickness_field);
      const CPLValueType kind = CPLGetValueType(text.c_str());
      if (kind != CPL_VALUE_REAL && kind != CPL_VALUE_INTEGER)
        fail("{}: thickness must be a number (in input-space units, e.g. 0.02), got '{}'", where,
             text);
      stroke.thickness = CPLAtof(text.c_str());
    }
  }
  return stroke;
}

}  // namespace

void check_sketch(const Sketch& sketch) {
  if (sketch.strokes.empty()) fail("{}: the sketch has no strokes", sketch.source);
  for (std::size_t i = 0; i < sketch.strokes.size(); ++i) {
    check_stroke(sketch.strokes[i],
                 fmt::format("{}: stroke {} (FID {})", sketch.source, i, sketch.strokes[i].fid));
  }
}

Sketch load_sketch(const std::filesystem::path& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> dataset(GDALDataset::Open(
      path.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  if (!dataset) fail("{}: cannot open as a vector sketch", path.string());
  if (dataset->GetLayerCount() < 1) fail("{}: no layer", path.string());
  Sketch sketch;
  sketch.source = path.string();
  OGRLayer* layer = dataset->GetLayer(0);
  layer->ResetReading();
  while (std::unique_ptr<OGRFeature> feature{layer->GetNextFeature()}) {
    const std::string where = fmt::format("{}: FID {}", path.string(), feature->GetFID());
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (!geometry) fail("{}: no geometry", where);
    const auto type = wkbFlatten(geometry->getGeometryType());
    if (type == wkbLineString) {
      sketch.strokes.push_back(stroke_from(*geometry->toLineString(), *feature, where));
    } else if (type == wkbMultiLineString) {
      for (const OGRLineString* part : *geometry->toMultiLineString()) {
        sketch.strokes.push_back(stroke_from(*part, *feature, where));
      }
    } else {
      fail("{}: a stroke must be a LineString, got {}", where, geometry->getGeometryName());
    }
  }
  check_sketch(sketch);
  return sketch;
}

}  // namespace tw
