// Unreal Engine landscape: a 16-bit grayscale PNG heightmap (square vertices: one spacing on X
// and Y, the world padded to the sizes, never stretched), an 8-bit weightmap per splat material,
// the visibility layer of the padding, the location and scale to type in (unreal.json), and the
// splines (Z scale and location: unreal_z).
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

namespace {

// Per axis the smallest recommended size holding the world's vertices at one spacing: the
// longer span fills its size, the shorter is padded up to its own.
EngineVertices unreal_vertices(const GridSpec& grid, int size) {
  if (size != 0)
    return engine_vertices(grid, size, size, fitting_spacing(grid, size, size),
                           OriginCorner::north_west);
  const int nx = engine_heightmap_size(Engine::unreal, grid.width);
  const int ny = engine_heightmap_size(Engine::unreal, grid.height);
  const double spacing = fitting_spacing(grid, nx, ny);
  const int mx = vertices_over((grid.width - 1) * grid.pixel_width, spacing);
  const int my = vertices_over((grid.height - 1) * grid.pixel_height, spacing);
  return engine_vertices(grid, engine_heightmap_size(Engine::unreal, mx),
                         engine_heightmap_size(Engine::unreal, my), spacing,
                         OriginCorner::north_west);
}

}  // namespace

EngineExportResult export_unreal(const ExportSource& source, const EngineExportOptions& options,
                                 const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  const EngineVertices v = unreal_vertices(grid, options.size);
  const int nx = v.width, ny = v.height;
  const Heightmap16 map = quantize_heights(on_engine(source.heights, grid, v));
  EngineExportResult result;
  const std::vector<int>& recommended = engine_heightmap_sizes(Engine::unreal);
  for (const int n : {nx, ny})
    if (!std::binary_search(recommended.begin(), recommended.end(), n)) {
      result.warnings.push_back(
          fmt::format("unreal: {} is not one of Epic's recommended sizes ({}): Unreal builds whole "
                      "components and pads the rest (or resamples, as the import dialog chooses)",
                      n, engine_size_text(Engine::unreal)));
      break;
    }
  result.files.push_back(dir / "heightmap.png");
  write_png16(stager.stage(result.files.back()), map);

  nlohmann::json layers = nlohmann::json::array();
  std::vector<std::vector<std::uint8_t>> weights;
  std::vector<std::string> names;
  if (source.splat != nullptr) {
    weights = quantize_weights(engine_weights(source, v));
    names = material_names(source.splat->channels);
    for (std::size_t m = 0; m < weights.size(); ++m) {
      const std::string file = "weightmap_" + names[m] + ".png";
      result.files.push_back(dir / file);
      write_png(stager.stage(result.files.back()), nx, ny, {weights[m].data()});
      layers.push_back({{"material", names[m]}, {"file", file}});
    }
  }
  nlohmann::json padding = padding_json(v);
  if (v.padded()) {
    // Unreal's Visibility layer: 255 makes a hole (with a landscape hole material).
    std::vector<std::uint8_t> holes = world_mask(v);
    for (std::uint8_t& h : holes) h = std::uint8_t(255 - h);
    result.files.push_back(dir / "visibility.png");
    write_png(stager.stage(result.files.back()), nx, ny, {holes.data()});
    padding["visibility"] = "visibility.png";
  }
  const double scale_xy = v.spacing * 100.0;
  const UnrealZ z = unreal_z(map.min, map.max);
  const double scale_z = z.scale, location_z = z.location_cm;
  // Vertex (0, 0), the landscape's corner at Location (0, 0): the world's north-west centre.
  const EngineFrame frame = engine_frame(Engine::unreal, grid);
  nlohmann::json sidecar = {{"engine", "unreal"},
                            {"heightmap", "heightmap.png"},
                            {"size", {nx, ny}},
                            {"location_cm", {0.0, 0.0, location_z}},
                            {"scale", {scale_xy, scale_xy, scale_z}},
                            {"height_min_m", map.min},
                            {"height_max_m", map.max},
                            {"height_step_m", map.step()},
                            {"world_origin", frame.origin},
                            {"padding", padding},
                            {"crs_wkt", source.set.crs_wkt},
                            {"weightmaps", layers}};
  if (source.input_heights != nullptr)
    sidecar["layers"] =
        write_edit_layers(source, v, weights, v, names, map.step(), dir, stager, result);
  result.files.push_back(dir / "unreal.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);

  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);

  result.settings = {
      fmt::format("unreal: import {} ({} x {}) as a landscape", (dir / "heightmap.png").string(),
                  nx, ny),
      fmt::format("unreal: Location X 0 Y 0 Z {:.3f}", location_z),
      fmt::format("unreal: Scale X {:.4f} Y {:.4f} Z {:.4f}", scale_xy, scale_xy, scale_z),
      fmt::format("unreal: heights {:.3f} .. {:.3f} m, {:.5f} m per step", map.min, map.max,
                  map.step())};
  if (v.padded())
    result.settings.push_back(fmt::format(
        "unreal: the world is vertices 0 .. {} x 0 .. {}; the rest is padding (edge heights, "
        "visibility.png marks it)",
        v.world.width - 1, v.world.height - 1));
  return result;
}

}  // namespace tw::detail
