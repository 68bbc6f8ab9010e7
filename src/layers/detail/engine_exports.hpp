#pragma once
// One function per engine (layers/export_<engine>.cpp) over what they share.
#include <filesystem>
#include <string>
#include <vector>

#include "core/atomic_output.hpp"
#include "layers/detail/splines.hpp"
#include "layers/export.hpp"

namespace tw::detail {

struct ExportSource {
  const LayerSet& set;
  Raster<float> heights;  // the height layer, nodata filled
  const Layer* splat;     // nullptr when the run has none
  const std::vector<ExportCurve>& curves;
};

// The material names of a splat layer's channels or band descriptions ("splat.road" -> "road"),
// for a layer in memory and for a layer file read by windows alike.
std::vector<std::string> material_names(const std::vector<std::string>& splat_channels);
// Each splat band resampled onto `to`.
std::vector<Raster<float>> resampled_weights(const ExportSource& source, const GridSpec& to);
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
EngineExportResult export_godot(const ExportSource& source, const EngineExportOptions& options,
                                const std::filesystem::path& dir, OutputStager& stager);

}  // namespace tw::detail
