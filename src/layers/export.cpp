// Engine exports: sizes, names, the shared preparation, and the dispatch to each engine.
#include "layers/export.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <algorithm>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "geo/resample.hpp"
#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"

namespace tw {

Engine parse_engine(std::string_view name) {
  if (name == "unreal") return Engine::unreal;
  if (name == "unity") return Engine::unity;
  if (name == "godot") return Engine::godot;
  if (name == "terrain3d") return Engine::terrain3d;
  fail("unknown engine '{}', expected unreal, unity, godot or terrain3d", name);
}

std::string to_string(Engine engine) {
  switch (engine) {
    case Engine::unreal:
      return "unreal";
    case Engine::unity:
      return "unity";
    case Engine::godot:
      return "godot";
    case Engine::terrain3d:
      return "terrain3d";
  }
  return "unreal";
}

const std::vector<int>& engine_heightmap_sizes(Engine engine) {
  // Epic's "recommended landscape sizes" (Landscape Technical Guide): whole components.
  static const std::vector<int> unreal = {127, 253, 505, 1009, 2017, 4033, 8129};
  static const std::vector<int> power_of_two_plus_one = {33, 65, 129, 257, 513, 1025, 2049, 4097};
  return engine == Engine::unreal ? unreal : power_of_two_plus_one;
}

int export_tile_size(const EngineExportOptions& options, int run_tile_size) {
  if (options.tile_size) return *options.tile_size;
  if (run_tile_size <= 0 || options.engine == Engine::godot || options.engine == Engine::terrain3d)
    return 0;
  return engine_heightmap_size(options.engine, run_tile_size + 1);
}

bool engine_takes_size(Engine engine, int size) {
  if (engine == Engine::unreal) return size >= 8 && size <= 8129;
  if (engine == Engine::terrain3d) return false;
  const std::vector<int>& sizes = engine_heightmap_sizes(engine);
  return std::binary_search(sizes.begin(), sizes.end(), size);
}

std::string engine_size_text(Engine engine) {
  const std::vector<int>& sizes = engine_heightmap_sizes(engine);
  if (engine == Engine::terrain3d) return "none (Terrain3D takes the world's cells as they are)";
  if (engine == Engine::unreal)
    return fmt::format("8 ... 8129 (Epic's recommended: {})", fmt::join(sizes, ", "));
  return fmt::format("{} ... {} (2^n + 1)", sizes.front(), sizes.back());
}

int engine_heightmap_size(Engine engine, int cells) {
  const std::vector<int>& sizes = engine_heightmap_sizes(engine);
  const auto it = std::lower_bound(sizes.begin(), sizes.end(), cells);
  return it == sizes.end() ? sizes.back() : *it;
}

EngineExportResult export_for_engine(const LayerSet& set, const std::vector<ExportCurve>& curves,
                                     const EngineExportOptions& options,
                                     const std::filesystem::path& dir, OutputStager& stager,
                                     const Raster<float>* input_height) {
  validate_layer_set(set);
  const Layer* height = find_layer(set, "height");
  const std::string engine = to_string(options.engine);
  if (height == nullptr) fail("export {}: the run has no height layer", engine);
  if (options.size != 0 && !engine_takes_size(options.engine, options.size))
    fail("export {}: size {} is not one the engine takes: {}", engine, options.size,
         engine_size_text(options.engine));
  if (options.layers && input_height == nullptr)
    fail(
        "export {}: layers need the heights before the run (--input-height, or the run's "
        "`export:` key)",
        engine);
  if (input_height != nullptr &&
      (input_height->width != set.grid.width || input_height->height != set.grid.height))
    fail("export {}: the input heights are {} x {}, the run's grid {} x {}", engine,
         input_height->width, input_height->height, set.grid.width, set.grid.height);
  detail::ExportSource source{
      set, detail::fill_nodata(height->bands.front(), options.nodata_height),
      find_layer(set, "splat"), curves, options.layers ? input_height : nullptr};
  switch (options.engine) {
    case Engine::unreal:
      return detail::export_unreal(source, options, dir, stager);
    case Engine::unity:
      return detail::export_unity(source, options, dir, stager);
    case Engine::godot:
      return detail::export_godot(source, options, dir, stager);
    case Engine::terrain3d:
      return detail::export_terrain3d(source, options, dir, stager);
  }
  return {};
}

namespace detail {

std::vector<std::string> material_names(const std::vector<std::string>& splat_channels) {
  std::vector<std::string> names;
  for (const std::string& c : splat_channels)
    names.push_back(c.starts_with("splat.") ? c.substr(6) : c);
  return names;
}

std::vector<Raster<float>> resampled_weights(const ExportSource& source, const GridSpec& to) {
  std::vector<Raster<float>> out;
  if (source.splat == nullptr) return out;
  for (const Raster<float>& band : source.splat->bands) {
    Raster<float> clean = band;  // NaN (nodata in the GeoTIFF) weighs nothing
    for (float& w : clean.pixels)
      if (std::isnan(w)) w = 0.0f;
    out.push_back(resample_band(clean, source.set.grid, to));
  }
  return out;
}

Raster<float> on_engine(const Raster<float>& band, const GridSpec& world, const EngineVertices& v,
                        std::optional<float> fill) {
  return pad_to_engine(resample_band(band, world, v.data), v, fill);
}

std::vector<Raster<float>> engine_weights(const ExportSource& source, const EngineVertices& v) {
  std::vector<Raster<float>> out = resampled_weights(source, v.data);
  for (Raster<float>& band : out) band = pad_to_engine(band, v);
  return out;
}

nlohmann::json padding_json(const EngineVertices& v) {
  return {{"spacing_m", v.spacing},
          {"world_window", {v.world.col0, v.world.row0, v.world.width, v.world.height}},
          {"fill",
           "edge: a padding sample repeats the nearest world sample on its row, then "
           "column; weights likewise"}};
}

HeightAt height_at(const ExportSource& source) {
  return [&source](Vec2 p) { return sample_height_bilinear(source.heights, source.set.grid, p); };
}

void write_json(const std::filesystem::path& path, const std::string& text, OutputStager& stager) {
  std::ofstream out(stager.stage(path), std::ios::binary);
  out << text;
  out.close();
  if (!out) fail("cannot write {}", path.string());
}

}  // namespace detail

}  // namespace tw
