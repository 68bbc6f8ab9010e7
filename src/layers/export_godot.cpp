// Godot (HTerrain): the height at 2^n + 1 square (square vertices, the world padded) as a 32-bit
// float EXR (channel R, metres, what Image::load_exr reads) or R16 (16-bit little-endian, row 0
// north, min -> 0, max -> 65535), HTerrain-style splat maps (RGBA 8-bit, materials four by four,
// weights summing to 255 per pixel) at the heightmap's resolution, and godot.json with the map
// scale.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"

namespace tw::detail {

EngineExportResult export_godot(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  const int n = options.size
                    ? options.size
                    : engine_heightmap_size(Engine::godot, std::max(grid.width, grid.height));
  // Square: one spacing on x and z, the longer side filling the heightmap, the shorter padded
  // south or east (the terrain's corner stays the world's north-west cell centre).
  const EngineVertices v =
      engine_vertices(grid, n, n, fitting_spacing(grid, n, n), OriginCorner::north_west);
  const Raster<float> heights = on_engine(source.heights, grid, v);
  const Heightmap16 map = quantize_heights(heights);
  EngineExportResult result;
  const bool exr = options.godot_height == GodotHeightFormat::exr;
  const std::string height_file = exr ? "height.exr" : "height.r16";
  result.files.push_back(dir / height_file);
  if (exr)
    write_float_exr(stager.stage(result.files.back()), n, n, heights.pixels.data());
  else
    write_raw16(stager.stage(result.files.back()), map, false);

  nlohmann::json layers = nlohmann::json::array();
  std::vector<std::vector<std::uint8_t>> weights;
  std::vector<std::string> names;
  if (source.splat != nullptr) {
    weights = quantize_weights(engine_weights(source, v));
    names = material_names(source.splat->channels);
    const std::vector<std::uint8_t> zero(std::size_t(n) * n, 0);
    for (std::size_t first = 0; first < weights.size(); first += 4) {
      const std::string file = fmt::format("splat_{}.png", first / 4);
      std::vector<const std::uint8_t*> rgba;
      for (std::size_t m = first; m < first + 4; ++m) {
        rgba.push_back(m < weights.size() ? weights[m].data() : zero.data());
        if (m < weights.size())
          layers.push_back({{"material", names[m]},
                            {"splat", file},
                            {"channel", std::string(1, "RGBA"[m % 4])}});
      }
      result.files.push_back(dir / file);
      write_png(stager.stage(result.files.back()), n, n, rgba);
    }
  }
  const EngineFrame frame = engine_frame(Engine::godot, grid);
  if (v.padded()) {
    result.files.push_back(dir / "mask.png");
    write_png(stager.stage(result.files.back()), n, n, {world_mask(v).data()});
  }
  nlohmann::json sidecar = {{"engine", "godot"},
                            {"height", height_file},
                            {"resolution", n},
                            {"map_scale", {v.spacing, 1.0, v.spacing}},
                            {"padding", padding_json(v)},
                            {"height_min_m", map.min},
                            {"height_max_m", map.max},
                            {"world_origin", frame.origin},
                            {"crs_wkt", source.set.crs_wkt},
                            {"splat", layers}};
  if (v.padded()) sidecar["padding"]["mask"] = "mask.png";
  if (source.input_heights != nullptr)
    sidecar["layers"] = write_edit_layers(source, v, weights, v, names, 0.0, dir, stager, result);
  result.files.push_back(dir / "godot.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);
  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);
  result.settings = {
      fmt::format("godot: import {} ({} x {}{})", (dir / height_file).string(), n, n,
                  exr ? ", metres" : fmt::format(", min {:.3f} max {:.3f}", map.min, map.max)),
      fmt::format("godot: HTerrain map_scale ({:.4f}, 1, {:.4f})", v.spacing, v.spacing)};
  return result;
}

}  // namespace tw::detail
