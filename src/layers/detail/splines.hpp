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
};

// The heights of the points are the terrain's (`heights` over `grid`, nodata filled) under
// them. Returns the final paths written, staged in `stager`.
std::vector<std::filesystem::path> write_splines(const std::vector<ExportCurve>& curves,
                                                 const Raster<float>& heights, const GridSpec& grid,
                                                 const EngineFrame& frame,
                                                 const std::filesystem::path& dir,
                                                 OutputStager& stager);

}  // namespace tw::detail
