#pragma once
// What a pipeline that parse_pipeline accepted must hold (docs/pipeline.md): the stages trust
// these without checking again.
#include "fuzz_support.hpp"
#include "pipeline/config.hpp"

namespace tw::fuzz {

inline void expect_positive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) broken_promise(what);
}

inline void check_pipeline(const PipelineConfig& config) {
  if (!config.heightfield) {
    if (config.generate.width <= 0 || config.generate.height <= 0)
      broken_promise("generate: size <= 0");
    expect_positive(config.generate.pixel_size, "generate.pixel_size");
    expect_finite(config.generate.relief, "generate.relief");
    expect_finite(config.generate.origin_x, "generate.origin x");
    expect_finite(config.generate.origin_y, "generate.origin y");
  }
  if (config.resolution) expect_positive(*config.resolution, "resolution");
  expect_positive(config.synthesis_resolution, "synthesis_resolution");
  if (config.region) {
    const RegionConfig& r = *config.region;
    expect_finite(r.min_x, "region");
    expect_finite(r.min_y, "region");
    expect_finite(r.max_x, "region");
    expect_finite(r.max_y, "region");
    if (!(r.min_x < r.max_x && r.min_y < r.max_y)) broken_promise("region: empty");
  }
  for (const FeatureClassConfig& c : config.features) {
    if (c.name.empty()) broken_promise("features: a class without a name");
    if (c.width_attribute.empty()) {
      expect_positive(c.width, "features.*.width");
    } else if (!(std::isfinite(c.width) && c.width >= 0.0)) {
      broken_promise("features.*.width (fallback of width_attribute)");
    }
    if (const SynthesisConfig* synthesis =
            method_options<SynthesisConfig>(c, kPatternsMethodName)) {
      const SynthesisConfig& s = *synthesis;
      if (s.exemplars.empty()) broken_promise("synthesis: no exemplar");
      // delta and min_coverage are optional: absent, the exemplar's defaults apply later
      // (synthesis_defaults); given, they must be usable as they are.
      if (s.delta) expect_positive(*s.delta, "synthesis.delta");
      expect_positive(s.scale, "synthesis.scale");
      if (s.width) expect_positive(*s.width, "synthesis.width");
      if (s.min_coverage && !(*s.min_coverage >= 0.0 && *s.min_coverage <= 1.0))
        broken_promise("synthesis.min_coverage outside [0, 1]");
      if (!(std::isfinite(s.feather) && s.feather >= 0.0)) broken_promise("synthesis.feather");
      expect_finite(s.height_detail, "synthesis.height_detail");
    }
  }
  for (const ExistingConfig& e : config.existing) {
    if (!(std::isfinite(e.width) && e.width >= 0.0)) broken_promise("existing.width");
  }
}

}  // namespace tw::fuzz
