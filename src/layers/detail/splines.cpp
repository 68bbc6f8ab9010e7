#include "layers/detail/splines.hpp"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace tw::detail {

EngineFrame engine_frame(Engine engine, const GridSpec& world) {
  const double x0 = world.origin_x + world.pixel_width / 2.0;
  const double north = world.origin_y - world.pixel_height / 2.0;
  const double south = world.origin_y - (world.height - 0.5) * world.pixel_height;
  switch (engine) {
    case Engine::unity:
      return {"unity",
              "x east, y up, z north; metres from the terrain corner",
              1.0,
              [x0, south](double x, double y, double h) {
                return std::array<double, 3>{x - x0, h, y - south};
              },
              {x0, south}};
    case Engine::godot:
      return {"godot",
              "x east, y up, z south; metres from the terrain corner",
              1.0,
              [x0, north](double x, double y, double h) {
                return std::array<double, 3>{x - x0, h, north - y};
              },
              {x0, north}};
    case Engine::unreal:
      break;
  }
  return {"unreal",
          "X east, Y south, Z up; centimetres from the landscape corner",
          100.0,
          [x0, north](double x, double y, double h) {
            return std::array<double, 3>{(x - x0) * 100.0, (north - y) * 100.0, h * 100.0};
          },
          {x0, north}};
}

std::vector<std::filesystem::path> write_splines(const std::vector<ExportCurve>& curves,
                                                 const HeightAt& height_at,
                                                 const EngineFrame& frame,
                                                 const std::filesystem::path& dir,
                                                 OutputStager& stager) {
  nlohmann::json splines = nlohmann::json::array();
  std::string csv = "Name,Spline,Class,Kind,Fid,Point,X,Y,Z,Width,WorldX,WorldY,Height\n";
  for (std::size_t s = 0; s < curves.size(); ++s) {
    const ExportCurve& curve = curves[s];
    const std::string name = fmt::format("{}_{}", curve.feature_class, curve.fid);
    nlohmann::json points = nlohmann::json::array();
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const Vec2 p = curve.points[i];
      double h = height_at(p);
      if (std::isnan(h)) h = 0.0;  // off the grid: a clipped line's end
      const auto e = frame.to_engine(p.x, p.y, h);
      points.push_back({{"world", {p.x, p.y, h}}, {"engine", {e[0], e[1], e[2]}}});
      csv +=
          fmt::format("{}_{}_{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}\n",
                      name, s, i, name, curve.feature_class, curve.kind, curve.fid, i, e[0], e[1],
                      e[2], curve.width * frame.unit, p.x, p.y, h);
    }
    splines.push_back({{"name", name},
                       {"class", curve.feature_class},
                       {"kind", curve.kind},
                       {"fid", curve.fid},
                       {"width_m", curve.width},
                       {"width", curve.width * frame.unit},
                       {"points", std::move(points)}});
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
