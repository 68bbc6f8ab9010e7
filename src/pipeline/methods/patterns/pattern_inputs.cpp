#include "pipeline/methods/patterns/pattern_inputs.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/detail/exemplar_memo.hpp"
#include "pipeline/methods/patterns/pattern_config.hpp"
#include "pipeline/methods/patterns/patterns.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"

namespace tw::detail {

void resolve_exemplar_defaults(PipelineConfig& config) {
  for (FeatureClassConfig& feature_class : config.features) {
    SynthesisConfig* found =
        find_method_options<SynthesisConfig>(feature_class.methods, kPatternsMethodName);
    if (!found) continue;
    SynthesisConfig& s = *found;
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
}

bool check_exemplar_input(const InputFile& input, InputCheck& check) {
  if (input.kind != InputFile::Kind::method || input.role != kExemplarRole) return false;
  // One validated before with these bytes (and height twin) is not decoded again.
  const std::optional<std::filesystem::path>& cache_dir = check.cache_dir();
  const std::optional<ContentHash> hash =
      cache_dir ? std::optional(exemplar_file_hash(input.path)) : std::nullopt;
  if (hash && remembered_exemplar(*cache_dir, *hash, input.path)) return true;
  Exemplar exemplar;
  try {
    exemplar = load_exemplar_with_height(input.path, false);
  } catch (const Error& e) {
    fail("{}: cannot be used as an exemplar: {}", input.named_at, e.what());
  }
  if (hash) remember_exemplar(check.cache_folder(), *cache_dir, *hash, exemplar);
  return true;
}

}  // namespace tw::detail
