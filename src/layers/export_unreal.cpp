// Unreal Engine landscape: a 16-bit grayscale PNG heightmap at one of Epic's landscape sizes,
// an 8-bit weightmap per splat material, the location and scale to type in (unreal.json), and
// the splines (Z scale and location: unreal_z).
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"

namespace tw::detail {

UnrealZ unreal_z(double min, double max) {
  const double scale = (max - min) * 100.0 * 128.0 / 65535.0;
  return {scale, min * 100.0 + 32768.0 * scale / 128.0};
}

EngineExportResult export_unreal(const ExportSource& source, const EngineExportOptions& options,
                                 const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  const int nx = options.size ? options.size : engine_heightmap_size(Engine::unreal, grid.width);
  const int ny = options.size ? options.size : engine_heightmap_size(Engine::unreal, grid.height);
  const GridSpec vertices = vertex_grid(grid, nx, ny);
  const Heightmap16 map = quantize_heights(resample_band(source.heights, grid, vertices));
  EngineExportResult result;
  result.files.push_back(dir / "heightmap.png");
  write_png16(stager.stage(result.files.back()), map);

  nlohmann::json layers = nlohmann::json::array();
  if (source.splat != nullptr) {
    const auto weights = quantize_weights(resampled_weights(source, vertices));
    const auto names = material_names(source.splat->channels);
    for (std::size_t m = 0; m < weights.size(); ++m) {
      const std::string file = "weightmap_" + names[m] + ".png";
      result.files.push_back(dir / file);
      write_png(stager.stage(result.files.back()), nx, ny, {weights[m].data()});
      layers.push_back({{"material", names[m]}, {"file", file}});
    }
  }
  const double scale_x = vertices.pixel_width * 100.0, scale_y = vertices.pixel_height * 100.0;
  const UnrealZ z = unreal_z(map.min, map.max);
  const double scale_z = z.scale, location_z = z.location_cm;
  // Vertex (0, 0), the landscape's corner at Location (0, 0): the world's north-west centre.
  const EngineFrame frame = engine_frame(Engine::unreal, grid);
  const nlohmann::json sidecar = {{"engine", "unreal"},
                                  {"heightmap", "heightmap.png"},
                                  {"size", {nx, ny}},
                                  {"location_cm", {0.0, 0.0, location_z}},
                                  {"scale", {scale_x, scale_y, scale_z}},
                                  {"height_min_m", map.min},
                                  {"height_max_m", map.max},
                                  {"height_step_m", map.step()},
                                  {"world_origin", frame.origin},
                                  {"crs_wkt", source.set.crs_wkt},
                                  {"weightmaps", layers}};
  result.files.push_back(dir / "unreal.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);

  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);

  result.settings = {
      fmt::format("unreal: import {} ({} x {}) as a landscape", (dir / "heightmap.png").string(),
                  nx, ny),
      fmt::format("unreal: Location X 0 Y 0 Z {:.3f}", location_z),
      fmt::format("unreal: Scale X {:.4f} Y {:.4f} Z {:.4f}", scale_x, scale_y, scale_z),
      fmt::format("unreal: heights {:.3f} .. {:.3f} m, {:.5f} m per step", map.min, map.max,
                  map.step())};
  return result;
}

}  // namespace tw::detail
