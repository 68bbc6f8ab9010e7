#pragma once
// Road and river centerlines as engine splines: splines.json (control points in world and
// engine coordinates, widths, heights) and splines.csv (one row per point, an Unreal data
// table's layout: the first column is the row name).
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/atomic_output.hpp"
#include "core/grid.hpp"
#include "layers/export.hpp"

namespace tw::detail {

struct EngineFrame {
  std::string engine;  // unreal, unity, godot
  std::string axes;    // e.g. "X east, Y south, Z up, centimetres"
  double unit = 1.0;   // engine units per metre (widths)
  // (world x, world y, height in metres) -> engine coordinates.
  std::function<std::array<double, 3>(double, double, double)> to_engine;
  std::array<double, 2> origin{};  // the world point at the engine's (0, 0): a corner centre
  // The terrain's extent in the engine, world metres: west, south, east, north cell centres.
  std::array<double, 4> extent{};
};

// The engine's frame over `world` (the run's grid): Unreal X east, Y south, Z up, cm from the
// north-west cell centre; Unity x east, y up, z north, metres from the south-west one; Godot
// x east, y up, z south, metres from the north-west one.
EngineFrame engine_frame(Engine engine, const GridSpec& world);

// The terrain's height (metres, nodata filled) at a world point; NaN off the grid.
using HeightAt = std::function<double(Vec2)>;

// Each curve is clipped to the frame's extent (a line that leaves it and comes back gives one
// spline per part, named <class>_<fid>_<part>); the heights of the points are the terrain's
// under them (a point without one is an error, never 0). Returns the final paths written,
// staged in `stager`.
std::vector<std::filesystem::path> write_splines(const std::vector<ExportCurve>& curves,
                                                 const HeightAt& height_at,
                                                 const EngineFrame& frame,
                                                 const std::filesystem::path& dir,
                                                 OutputStager& stager);

}  // namespace tw::detail
