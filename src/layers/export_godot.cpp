// Godot (HTerrain, Terrain3D): the height at 2^n + 1 square as a 32-bit float EXR (channel R,
// metres, what Image::load_exr reads) or R16 (16-bit little-endian, row 0 north, min -> 0,
// max -> 65535), HTerrain-style splat maps (RGBA 8-bit, materials four by four, weights
// summing to 255 per pixel) at the heightmap's resolution, and godot.json with the map scale.
#include <fmt/format.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"

namespace tw::detail {

namespace {

// Through OpenEXR itself: OpenImageIO's writer stamps a capDate of the current time, and an
// export must be the same bytes on every run.
void write_float_exr(const std::filesystem::path& path, const Raster<float>& heights) {
  try {
    Imf::Header header(heights.width, heights.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    // const_cast: OpenEXR's Slice takes char* for reading and writing alike; it only reads.
    char* base = reinterpret_cast<char*>(const_cast<float*>(heights.pixels.data()));
    frame.insert("R", Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                 sizeof(float) * std::size_t(heights.width)));
    file.setFrameBuffer(frame);
    file.writePixels(heights.height);
  } catch (const std::exception& e) {
    fail("cannot write {}: {}", path.string(), e.what());
  }
}

}  // namespace

EngineExportResult export_godot(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  const int n = options.size
                    ? options.size
                    : engine_heightmap_size(Engine::godot, std::max(grid.width, grid.height));
  const GridSpec vertices = vertex_grid(grid, n, n);
  const Raster<float> heights = resample_band(source.heights, grid, vertices);
  const Heightmap16 map = quantize_heights(heights);
  EngineExportResult result;
  const bool exr = options.godot_height == GodotHeightFormat::exr;
  const std::string height_file = exr ? "height.exr" : "height.r16";
  result.files.push_back(dir / height_file);
  if (exr)
    write_float_exr(stager.stage(result.files.back()), heights);
  else
    write_raw16(stager.stage(result.files.back()), map, false);

  nlohmann::json layers = nlohmann::json::array();
  if (source.splat != nullptr) {
    const auto weights = quantize_weights(resampled_weights(source, vertices));
    const auto names = material_names(source.splat->channels);
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
  const nlohmann::json sidecar = {{"engine", "godot"},
                                  {"height", height_file},
                                  {"resolution", n},
                                  {"map_scale", {vertices.pixel_width, 1.0, vertices.pixel_height}},
                                  {"height_min_m", map.min},
                                  {"height_max_m", map.max},
                                  {"world_origin", frame.origin},
                                  {"crs_wkt", source.set.crs_wkt},
                                  {"splat", layers}};
  result.files.push_back(dir / "godot.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);
  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);
  result.settings = {
      fmt::format("godot: import {} ({} x {}{})", (dir / height_file).string(), n, n,
                  exr ? ", metres" : fmt::format(", min {:.3f} max {:.3f}", map.min, map.max)),
      fmt::format("godot: HTerrain map_scale ({:.4f}, 1, {:.4f})", vertices.pixel_width,
                  vertices.pixel_height)};
  return result;
}

}  // namespace tw::detail
