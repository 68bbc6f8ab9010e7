#include "terrain/detail/structures.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "terrain/detail/profiles.hpp"

namespace tw::detail {
namespace {

bool is_structure_road(const TerrainFeature& f) {
  return f.kind == FeatureKind::road && f.structure != Structure::ground;
}

}  // namespace

void drop_road_structure_contacts(const std::vector<TerrainFeature>& features,
                                  std::vector<std::vector<EndContact>>& contacts) {
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (features[i].kind != FeatureKind::road) continue;
    std::erase_if(contacts[i], [&](const EndContact& c) {
      return is_structure_road(features[i]) || is_structure_road(features[std::size_t(c.other)]);
    });
  }
}

void lay_decks(const std::vector<TerrainFeature>& features, const std::vector<double>& steps,
               const std::vector<std::vector<EndContact>>& contacts,
               std::vector<std::vector<double>>& profiles) {
  // ends[i][0] at the start, [1] at the end; filled from ground roads first.
  std::vector<std::array<std::optional<double>, 2>> ends(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!is_structure_road(features[i]) || features[i].width <= 0.0) continue;
    for (const bool at_start : {true, false}) {
      double sum = 0.0;
      int count = 0;
      for (const EndContact& c : contacts[i]) {
        const std::size_t j = std::size_t(c.other);
        if (c.at_start != at_start || is_structure_road(features[j]) || features[j].width <= 0.0)
          continue;
        sum += profile_at(profiles[j], steps[j], c.other_s);
        ++count;
      }
      if (count > 0) ends[i][at_start ? 0 : 1] = sum / count;
    }
  }
  // A structure split into several ways: an open end takes the resolved end it touches.
  for (std::size_t pass = 0; pass < features.size(); ++pass) {
    bool changed = false;
    for (std::size_t i = 0; i < features.size(); ++i) {
      if (!is_structure_road(features[i]) || features[i].width <= 0.0) continue;
      for (const bool at_start : {true, false}) {
        auto& end = ends[i][at_start ? 0 : 1];
        if (end) continue;
        for (const EndContact& c : contacts[i]) {
          const std::size_t j = std::size_t(c.other);
          if (c.at_start != at_start || !c.other_end || !is_structure_road(features[j])) continue;
          const auto& other = ends[j][c.other_s == 0.0 ? 0 : 1];
          if (!other) continue;
          end = *other;
          changed = true;
          break;
        }
      }
    }
    if (!changed) break;
  }
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!is_structure_road(features[i]) || features[i].width <= 0.0) continue;
    auto& p = profiles[i];
    const double start = ends[i][0].value_or(p.front());
    const double finish = ends[i][1].value_or(p.back());
    const double last = double(std::max<std::size_t>(p.size(), 2) - 1);
    for (std::size_t k = 0; k < p.size(); ++k) p[k] = start + (finish - start) * (double(k) / last);
  }
}

}  // namespace tw::detail
