#pragma once
// One function per engine (layers/export_<engine>.cpp) over what they share.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/atomic_output.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"
#include "layers/export.hpp"

namespace tw::detail {

struct ExportSource {
  const LayerSet& set;
  Raster<float> heights;  // the height layer, nodata filled
  const Layer* splat;     // nullptr when the run has none
  const std::vector<ExportCurve>& curves;
  const Raster<float>* input_heights = nullptr;  // options.layers: before the run, NaN = nodata
};

// The material names of a splat layer's channels or band descriptions ("splat.road" -> "road"),
// for a layer in memory and for a layer file read by windows alike.
std::vector<std::string> material_names(const std::vector<std::string>& splat_channels);
// Each splat band resampled onto `to`.
std::vector<Raster<float>> resampled_weights(const ExportSource& source, const GridSpec& to);
// A nodata-free band of the world on the engine's samples: resampled onto the world's ones,
// the padding carrying the edge on (or `fill`).
Raster<float> on_engine(const Raster<float>& band, const GridSpec& world, const EngineVertices& v,
                        std::optional<float> fill = std::nullopt);
// Each splat band on the engine's samples (nodata weighs nothing; padding: the edge's weights).
std::vector<Raster<float>> engine_weights(const ExportSource& source, const EngineVertices& v);
// The sidecar's "padding": the world's window of the samples, the fill, the spacing.
nlohmann::json padding_json(const EngineVertices& v);
// Non-destructive layers into dir/layers (export_layers.cpp): height_delta.exr (result - input,
// metres, on `v`, 0 on padding and where either is nodata), with step_m > 0 also
// height_delta.png (16 bits, 32768 = no change, step_m metres per unit: an Unreal edit layer at
// the heightmap's Z scale), and weight_<material>.png for every material but the first (the
// untouched ground), the export's own 8-bit weights (on `weights_on`). Returns the sidecar's
// "layers" entry.
nlohmann::json write_edit_layers(const ExportSource& source, const EngineVertices& v,
                                 const std::vector<std::vector<std::uint8_t>>& weights,
                                 const EngineVertices& weights_on,
                                 const std::vector<std::string>& materials, double step_m,
                                 const std::filesystem::path& dir, OutputStager& stager,
                                 EngineExportResult& result);
// The filled height layer read bilinearly (the splines' heights).
HeightAt height_at(const ExportSource& source);
// Writes `json` (pretty) to dir/name, staged.
void write_json(const std::filesystem::path& path, const std::string& text, OutputStager& stager);

// Unreal's landscape Z: a 16-bit value v lies at Location.Z + (v - 32768) * Scale.Z / 128 cm
// (Epic's Landscape Technical Guide). Solved for v = 0 at `min` and v = 65535 at `max` metres,
// the quantization's ends, so every value lands on its true height (Epic's rounder
// "(max - min) * 100 / 512" puts 65535 one step below max).
struct UnrealZ {
  double scale = 0.0;        // Scale.Z
  double location_cm = 0.0;  // Location.Z
};
UnrealZ unreal_z(double min, double max);

EngineExportResult export_unreal(const ExportSource& source, const EngineExportOptions& options,
                                 const std::filesystem::path& dir, OutputStager& stager);
EngineExportResult export_unity(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager);
EngineExportResult export_terrain3d(const ExportSource& source, const EngineExportOptions& options,
                                    const std::filesystem::path& dir, OutputStager& stager);
EngineExportResult export_godot(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager);

}  // namespace tw::detail
