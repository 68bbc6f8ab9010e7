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
      const TerrainFeature& other = features[std::size_t(c.other)];
      // A road ending on another's side on a different layer passes over or under it.
      const bool other_layer = !c.other_end && other.layer != features[i].layer;
      return is_structure_road(features[i]) || is_structure_road(other) || other_layer;
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
  // Structures joined end to end (a bridge split into several ways) form one chain whose deck
  // runs straight, by arc length, between the chain's two outer ends.
  struct Link {
    int other = -1;
    bool other_at_start = false;
  };
  std::vector<std::array<Link, 2>> links(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!is_structure_road(features[i]) || features[i].width <= 0.0) continue;
    for (const EndContact& c : contacts[i]) {
      const std::size_t j = std::size_t(c.other);
      if (!c.other_end || !is_structure_road(features[j]) || features[j].width <= 0.0) continue;
      Link& link = links[i][c.at_start ? 0 : 1];
      if (link.other < 0) link = {int(j), c.other_s == 0.0};
    }
  }
  auto length_of = [&](std::size_t i) { return double(profiles[i].size() - 1) * steps[i]; };
  std::vector<char> laid(features.size(), 0);
  auto lay_chain = [&](std::size_t first, bool forward) {
    std::vector<std::pair<std::size_t, bool>> chain;  // (feature, runs along the chain)
    for (std::size_t i = first; !laid[i];) {
      laid[i] = 1;
      chain.emplace_back(i, forward);
      const Link next = links[i][forward ? 1 : 0];
      if (next.other < 0) break;
      i = std::size_t(next.other);
      forward = next.other_at_start;
    }
    auto outer = [&](std::size_t i, bool at_start) {
      return ends[i][at_start ? 0 : 1].value_or(at_start ? profiles[i].front()
                                                         : profiles[i].back());
    };
    const double h0 = outer(chain.front().first, chain.front().second);
    const double h1 = outer(chain.back().first, !chain.back().second);
    double total = 0.0;
    for (const auto& [i, f] : chain) total += length_of(i);
    double s = 0.0;
    for (const auto& [i, f] : chain) {
      auto& p = profiles[i];
      for (std::size_t k = 0; k < p.size(); ++k) {
        const double along = s + double(f ? k : p.size() - 1 - k) * steps[i];
        p[k] = total > 0.0 ? h0 + (h1 - h0) * (along / total) : h0;
      }
      s += length_of(i);
    }
  };
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!is_structure_road(features[i]) || features[i].width <= 0.0 || laid[i]) continue;
    if (links[i][0].other < 0)
      lay_chain(i, true);
    else if (links[i][1].other < 0)
      lay_chain(i, false);
  }
  for (std::size_t i = 0; i < features.size(); ++i) {  // rings of structures: start anywhere
    if (is_structure_road(features[i]) && features[i].width > 0.0 && !laid[i]) lay_chain(i, true);
  }
}

}  // namespace tw::detail
