#include "pipeline/methods/patterns/pattern_bindings.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "geo/feature_selection.hpp"

namespace tw::detail {

std::vector<std::vector<std::uint8_t>> binding_matches(const FeatureClassConfig& feature_class,
                                                       const std::vector<LineFeature>& lines) {
  std::vector<std::vector<std::uint8_t>> matches;
  const SynthesisConfig* synthesis =
      method_options<SynthesisConfig>(feature_class, kPatternsMethodName);
  if (!synthesis) return matches;
  for (const ExemplarBinding& rule : synthesis->bind) {
    std::vector<std::uint8_t>& selected = matches.emplace_back(lines.size(), 1);
    const std::string where = selection_where(rule.tags, rule.where);
    if (where.empty()) continue;  // a junction rule on every line
    std::vector<std::int64_t> fids;
    try {
      fids = selected_fids({feature_class.source.string(), feature_class.layer, where});
    } catch (const Error& e) {
      fail("{}: {}", rule.key, e.what());
    }
    for (std::size_t f = 0; f < lines.size(); ++f)
      selected[f] = std::binary_search(fids.begin(), fids.end(), lines[f].fid) ? 1 : 0;
  }
  return matches;
}

std::vector<PieceBinding> feature_bindings(const SynthesisConfig& synthesis,
                                           const std::vector<std::vector<std::uint8_t>>& matches,
                                           std::size_t feature) {
  std::vector<PieceBinding> rules;
  for (std::size_t r = 0; r < synthesis.bind.size(); ++r) {
    const ExemplarBinding& b = synthesis.bind[r];
    rules.push_back({int(b.exemplar), matches.at(r).at(feature) != 0, b.near_junction});
  }
  return rules;
}

}  // namespace tw::detail
