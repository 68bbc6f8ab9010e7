// libFuzzer target: `--set` assignments (tw::parse_override), one per input line, applied
// through tw::parse_pipeline to a complete pipeline, so that a mutated key path reaches every
// section (generate, output, features.*.profile, features.*.synthesis, existing, region).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#include "pipeline/config.hpp"
#include "pipeline_invariants.hpp"

namespace {

constexpr std::string_view kBasePipeline = R"(version: 1
seed: 42
generate: { width: 64, height: 64, pixel_size: 4, relief: 120, crs: "EPSG:32631", origin: [500000, 5000000] }
resolution: 4
output: { dir: out, exr: true, geotiff: false, preview: false }
backend: cpu
precedence: [rivers, roads]
synthesis_resolution: 1
features:
  rivers:
    source: lines.geojson
    where: "kind = 'river'"
    kind: river
    width_attribute: width
    width: 10
    profile: { depth: 3, bank_width: 6, falloff: 20 }
  roads:
    source: lines.geojson
    kind: road
    width: 6
    profile: { max_grade: 0.06, shoulder_width: 2, falloff: 12, smoothing: 80 }
    synthesis:
      exemplar: lanes.png
      width: 10
      scale: 4
      delta: 14
      channels: { alpha: splat.road_marking }
existing:
  - { source: map.gpkg, layer: existing }
)";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<tw::Override> overrides;
    for (std::size_t begin = 0; begin <= input.size();) {
      std::size_t end = input.find('\n', begin);
      if (end == std::string_view::npos) end = input.size();
      const std::string_view line = input.substr(begin, end - begin);
      if (!line.empty()) overrides.push_back(tw::parse_override(line));
      begin = end + 1;
    }
    tw::fuzz::check_pipeline(tw::parse_pipeline(kBasePipeline, "base.yaml", "/fuzz", overrides));
  } catch (const tw::Error&) {
    // Refused with a message: the expected answer to a bad assignment.
  }
  return 0;
}
