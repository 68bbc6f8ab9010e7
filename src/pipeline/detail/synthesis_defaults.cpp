#include "pipeline/detail/synthesis_defaults.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/log.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"

namespace tw::detail {

namespace {
constexpr double kRibbonDelta = 4.0;  // metres: classes without synthesis
}  // namespace

PipelineConfig with_exemplar_defaults(PipelineConfig config) {
  for (FeatureClassConfig& feature_class : config.features) {
    if (!feature_class.synthesis) continue;
    SynthesisConfig& s = *feature_class.synthesis;
    const bool need_width = !s.width && !s.width_of_feature;
    if (!need_width && s.delta) continue;
    double width = 0.0, delta = 0.0;
    for (const auto& path : s.exemplars) {
      ExemplarOptions options;
      options.continuous_alpha = s.continuous_alpha;
      const ExemplarStats stats = exemplar_stats(load_exemplar(path.string(), options));
      if (stats.suggested_delta <= 0) {
        fail("features.{}.synthesis: exemplar {} implies no piece length; give `delta`",
             feature_class.name, path.string());
      }
      width = std::max(width, suggested_width(stats, s.scale));
      const double d = suggested_delta(stats, s.scale);
      delta = delta == 0.0 ? d : std::min(delta, d);
    }
    if (need_width) s.width = width, s.width_from_exemplar = true;
    if (!s.delta) s.delta = delta, s.delta_from_exemplar = true;
    logger().info("features.{}.synthesis: width {:.3g} m ({}), delta {:.3g} m ({})",
                  feature_class.name, s.width ? *s.width : 0.0,
                  s.width_of_feature      ? "the feature's"
                  : s.width_from_exemplar ? "from the exemplar"
                                          : "given",
                  *s.delta, s.delta_from_exemplar ? "from the exemplar" : "given");
  }
  return config;
}

double class_delta(const FeatureClassConfig& feature_class) {
  if (!feature_class.synthesis) return kRibbonDelta;
  if (!feature_class.synthesis->delta)
    fail("features.{}.synthesis: delta not resolved (with_exemplar_defaults)", feature_class.name);
  return *feature_class.synthesis->delta;
}

}  // namespace tw::detail
