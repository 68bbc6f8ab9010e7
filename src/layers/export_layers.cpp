// Non-destructive engine layers (docs/exports.md, "Layers over an existing terrain"): what the
// run changed, to apply over a terrain the engine already has (an Unreal Landscape edit layer
// or Landscape Patch, a Terrain3D script) instead of replacing it: the height delta (result -
// input, metres) and the weights of the materials the features painted.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"

namespace tw::detail {

nlohmann::json write_edit_layers(const ExportSource& source, const EngineVertices& v,
                                 const std::vector<std::vector<std::uint8_t>>& weights,
                                 const EngineVertices& weights_on,
                                 const std::vector<std::string>& materials, double step_m,
                                 const std::filesystem::path& dir, OutputStager& stager,
                                 EngineExportResult& result) {
  const Raster<float>& input = *source.input_heights;
  const Raster<float>& output = find_layer(source.set, "height")->bands.front();
  // Nodata on either side changes nothing: 0 (the filled heights are no run's work).
  Raster<float> delta(output.width, output.height, 0.0f);
  for (std::size_t i = 0; i < delta.pixels.size(); ++i)
    if (std::isfinite(output.pixels[i]) && std::isfinite(input.pixels[i]))
      delta.pixels[i] = output.pixels[i] - input.pixels[i];
  const Raster<float> on_v = on_engine(delta, source.set.grid, v, 0.0f);
  const std::filesystem::path folder = dir / "layers";
  nlohmann::json out = {{"height_delta", "layers/height_delta.exr"},
                        {"height_delta_units", "metres, result - input, 0 on padding"}};
  result.files.push_back(folder / "height_delta.exr");
  write_float_exr(stager.stage(result.files.back()), on_v.width, on_v.height, on_v.pixels.data());
  if (step_m > 0.0) {
    Heightmap16 png;
    png.width = on_v.width;
    png.height = on_v.height;
    png.pixels.resize(on_v.pixels.size());
    std::int64_t clipped = 0;
    for (std::size_t i = 0; i < png.pixels.size(); ++i) {
      const long value = 32768 + std::lround(on_v.pixels[i] / step_m);
      clipped += value < 0 || value > 65535;
      png.pixels[i] = std::uint16_t(std::clamp(value, 0L, 65535L));
    }
    if (clipped > 0)
      result.warnings.push_back(fmt::format(
          "{}: {} height-delta samples exceed +-32767 steps of {:.5f} m and were clipped",
          (folder / "height_delta.png").string(), clipped, step_m));
    result.files.push_back(folder / "height_delta.png");
    write_png16(stager.stage(result.files.back()), png);
    out["height_delta_png"] = "layers/height_delta.png";
    out["height_delta_png_step_m"] = step_m;
  }
  nlohmann::json files = nlohmann::json::array();
  const std::vector<std::uint8_t> world = world_mask(weights_on);
  for (std::size_t m = 1; m < weights.size(); ++m) {
    std::vector<std::uint8_t> layer = weights[m];
    for (std::size_t i = 0; i < layer.size(); ++i)
      if (world[i] == 0) layer[i] = 0;  // padding: nothing painted
    const std::string file = "weight_" + materials[m] + ".png";
    result.files.push_back(folder / file);
    write_png(stager.stage(result.files.back()), weights_on.width, weights_on.height,
              {layer.data()});
    files.push_back({{"material", materials[m]}, {"file", "layers/" + file}});
  }
  out["weights"] = files;
  return out;
}

}  // namespace tw::detail
