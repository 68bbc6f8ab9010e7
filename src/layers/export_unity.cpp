// Unity terrain: a RAW 16-bit little-endian heightmap at 2^n + 1, square vertices (Import Raw:
// Depth 16, Byte Order Windows, no Flip Vertically: row 0 of the file is the south edge, Unity's z
// = 0), splat control maps as RGBA 8-bit PNGs (materials four by four, in band order) at 2^n, and
// unity.json with the terrain size (x, height range, z) and position to set.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"

namespace tw::detail {

EngineExportResult export_unity(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  const int n = options.size
                    ? options.size
                    : engine_heightmap_size(Engine::unity, std::max(grid.width, grid.height));
  // Square: one spacing on x and z, the longer side filling the heightmap, the shorter padded
  // north (the terrain's corner stays the world's south-west cell centre).
  const double spacing = fitting_spacing(grid, n, n);
  const EngineVertices v = engine_vertices(grid, n, n, spacing, OriginCorner::south_west);
  const Heightmap16 map = quantize_heights(on_engine(source.heights, grid, v));
  EngineExportResult result;
  result.files.push_back(dir / "heightmap.raw");
  write_raw16(stager.stage(result.files.back()), map, true);

  const int alpha = n - 1;
  nlohmann::json layers = nlohmann::json::array();
  const EngineVertices texels =
      engine_texels(grid, alpha, alpha, spacing, OriginCorner::south_west);
  std::vector<std::vector<std::uint8_t>> weights;
  std::vector<std::string> names;
  if (source.splat != nullptr) {
    weights = quantize_weights(engine_weights(source, texels));
    names = material_names(source.splat->channels);
    const std::vector<std::uint8_t> zero(std::size_t(alpha) * alpha, 0);
    for (std::size_t first = 0; first < weights.size(); first += 4) {
      const std::string file = fmt::format("splatmap_{}.png", first / 4);
      std::vector<const std::uint8_t*> rgba;
      for (std::size_t m = first; m < first + 4; ++m) {
        rgba.push_back(m < weights.size() ? weights[m].data() : zero.data());
        if (m < weights.size())
          layers.push_back({{"material", names[m]},
                            {"control", file},
                            {"channel", std::string(1, "RGBA"[m % 4])}});
      }
      result.files.push_back(dir / file);
      write_png(stager.stage(result.files.back()), alpha, alpha, rgba);
    }
  }
  if (v.padded()) {
    result.files.push_back(dir / "mask.png");
    write_png(stager.stage(result.files.back()), n, n, {world_mask(v).data()});
  }
  const double size_x = (n - 1) * spacing, size_z = (n - 1) * spacing;
  const double range = map.max - map.min;
  // The terrain's corner (0, min, 0) is the world's south-west outer cell centre.
  const EngineFrame frame = engine_frame(Engine::unity, grid);
  nlohmann::json sidecar = {{"engine", "unity"},
                            {"heightmap", "heightmap.raw"},
                            {"heightmap_resolution", n},
                            {"depth", 16},
                            {"byte_order", "little-endian (Windows)"},
                            {"flip_vertically", false},
                            {"alphamap_resolution", alpha},
                            {"terrain_size", {size_x, range, size_z}},
                            {"position", {0.0, map.min, 0.0}},
                            {"height_min_m", map.min},
                            {"height_max_m", map.max},
                            {"world_origin", frame.origin},
                            {"padding", padding_json(v)},
                            {"crs_wkt", source.set.crs_wkt},
                            {"layers", layers}};
  if (v.padded()) sidecar["padding"]["mask"] = "mask.png";
  if (source.input_heights != nullptr)
    sidecar["edit_layers"] =
        write_edit_layers(source, v, weights, texels, names, 0.0, dir, stager, result);
  result.files.push_back(dir / "unity.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);
  // The terrain at (0, min, 0) with height `range`: a point's y is its height in metres.
  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);
  result.settings = {
      fmt::format("unity: Import Raw {} (Depth 16, Windows byte order, resolution {})",
                  (dir / "heightmap.raw").string(), n),
      fmt::format(
          "unity: Terrain Width {:.3f} Length {:.3f} Height {:.3f}; position (0, {:.3f}, 0)",
          size_x, size_z, range, map.min),
      fmt::format("unity: Control Texture Resolution {}", alpha)};
  return result;
}

}  // namespace tw::detail
