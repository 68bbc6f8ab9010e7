#include "layers/detail/splines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace tw::detail {

EngineFrame engine_frame(Engine engine, const GridSpec& world) {
  const double x0 = world.origin_x + world.pixel_width / 2.0;
  const double north = world.origin_y - world.pixel_height / 2.0;
  const double south = world.origin_y - (world.height - 0.5) * world.pixel_height;
  const double x1 = world.origin_x + (world.width - 0.5) * world.pixel_width;
  const std::array<double, 4> extent{x0, south, x1, north};
  switch (engine) {
    case Engine::unity:
      return {"unity",
              "x east, y up, z north; metres from the terrain corner",
              1.0,
              [x0, south](double x, double y, double h) {
                return std::array<double, 3>{x - x0, h, y - south};
              },
              {x0, south},
              extent};
    case Engine::godot:
    case Engine::terrain3d:
      return {engine == Engine::godot ? "godot" : "terrain3d",
              "x east, y up, z south; metres from the terrain corner",
              1.0,
              [x0, north](double x, double y, double h) {
                return std::array<double, 3>{x - x0, h, north - y};
              },
              {x0, north},
              extent};
    case Engine::unreal:
      break;
  }
  return {"unreal",
          "X east, Y south, Z up; centimetres from the landscape corner",
          100.0,
          [x0, north](double x, double y, double h) {
            return std::array<double, 3>{(x - x0) * 100.0, (north - y) * 100.0, h * 100.0};
          },
          {x0, north},
          extent};
}

namespace {

// The parts of a polyline inside the extent (west, south, east, north), in order along it.
std::vector<std::vector<Vec2>> clip_to_extent(const std::vector<Vec2>& points,
                                              const std::array<double, 4>& extent) {
  namespace bg = boost::geometry;
  using Point = bg::model::d2::point_xy<double>;
  const bg::model::box<Point> box({extent[0], extent[1]}, {extent[2], extent[3]});
  bg::model::linestring<Point> line;
  for (const Vec2 p : points) line.push_back({p.x, p.y});
  bg::model::multi_linestring<bg::model::linestring<Point>> parts;
  bg::intersection(box, line, parts);
  std::vector<std::vector<Vec2>> out;
  for (const auto& part : parts) {
    std::vector<Vec2> kept;
    for (const Point& q : part) {
      // Boost's crossing points may round a hair outside the box: onto its edge.
      const Vec2 p{std::clamp(q.x(), extent[0], extent[2]),
                   std::clamp(q.y(), extent[1], extent[3])};
      if (kept.empty() || !(kept.back() == p)) kept.push_back(p);
    }
    if (kept.size() >= 2) out.push_back(std::move(kept));
  }
  return out;
}

}  // namespace

std::vector<std::filesystem::path> write_splines(const std::vector<ExportCurve>& curves,
                                                 const HeightAt& height_at,
                                                 const EngineFrame& frame,
                                                 const std::filesystem::path& dir,
                                                 OutputStager& stager) {
  nlohmann::json splines = nlohmann::json::array();
  std::string csv = "Name,Spline,Class,Kind,Fid,Point,X,Y,Z,Width,WorldX,WorldY,Height\n";
  std::size_t s = 0;  // the spline's index in the files
  for (const ExportCurve& curve : curves) {
    const std::vector<std::vector<Vec2>> parts = clip_to_extent(curve.points, frame.extent);
    for (std::size_t part = 0; part < parts.size(); ++part, ++s) {
      const std::string name = parts.size() == 1
                                   ? fmt::format("{}_{}", curve.feature_class, curve.fid)
                                   : fmt::format("{}_{}_{}", curve.feature_class, curve.fid, part);
      nlohmann::json points = nlohmann::json::array();
      for (std::size_t i = 0; i < parts[part].size(); ++i) {
        const Vec2 p = parts[part][i];
        const double h = height_at(p);
        if (!std::isfinite(h))
          fail("splines: {} FID {} has no terrain height at ({:.3f}, {:.3f})", curve.feature_class,
               curve.fid, p.x, p.y);
        const auto e = frame.to_engine(p.x, p.y, h);
        points.push_back({{"world", {p.x, p.y, h}}, {"engine", {e[0], e[1], e[2]}}});
        csv += fmt::format(
            "{}_{}_{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}\n", name, s,
            i, name, curve.feature_class, curve.kind, curve.fid, i, e[0], e[1], e[2],
            curve.width * frame.unit, p.x, p.y, h);
      }
      splines.push_back({{"name", name},
                         {"class", curve.feature_class},
                         {"kind", curve.kind},
                         {"fid", curve.fid},
                         {"width_m", curve.width},
                         {"width", curve.width * frame.unit},
                         {"points", std::move(points)}});
    }
  }
  const nlohmann::json json = {{"engine", frame.engine},
                               {"axes", frame.axes},
                               {"units_per_metre", frame.unit},
                               {"splines", std::move(splines)}};
  const std::vector<std::filesystem::path> paths = {dir / "splines.json", dir / "splines.csv"};
  const std::string texts[] = {json.dump(2) + "\n", csv};
  for (std::size_t k = 0; k < paths.size(); ++k) {
    std::ofstream out(stager.stage(paths[k]), std::ios::binary);
    out << texts[k];
    out.close();
    if (!out) fail("cannot write {}", paths[k].string());
  }
  return paths;
}

}  // namespace tw::detail
