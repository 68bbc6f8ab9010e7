#include "synth/exemplar_mix.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "synth/detail/exemplar_mix.hpp"

namespace tw {

int MixLayout::exemplar_at(int ux, int uy) const {
  for (std::size_t e = 0; e < x0.size(); ++e)
    if (ux >= x0[e] && ux < x0[e] + width[e]) return uy < height[e] ? int(e) : -1;
  return -1;
}

int mix_gap(double scale, double delta, double width) {
  return int(std::ceil(2.0 * scale * (delta + width))) + 4;
}

std::vector<std::vector<std::uint8_t>> bind_pieces(const Ribbon& ribbon, int exemplar_count,
                                                   const std::vector<PieceBinding>& rules,
                                                   const std::vector<Vec2>& junctions) {
  std::vector<std::uint8_t> unbound(std::size_t(exemplar_count), 1);
  for (const PieceBinding& rule : rules) {
    if (rule.exemplar < 0 || rule.exemplar >= exemplar_count)
      fail("binding rule names exemplar {} of a mix of {}", rule.exemplar, exemplar_count);
    unbound[std::size_t(rule.exemplar)] = 0;
  }
  if (std::find(unbound.begin(), unbound.end(), 1) == unbound.end())
    unbound.assign(unbound.size(), 1);
  std::vector<std::vector<std::uint8_t>> out;
  for (const Piece& piece : ribbon.pieces) {
    const Vec2 left = lerp(piece.top_left, piece.bottom_left, 0.5);
    const Vec2 right = lerp(piece.top_right, piece.bottom_right, 0.5);
    const PieceBinding* bound = nullptr;
    for (const PieceBinding& rule : rules) {
      if (!rule.line_matches) continue;
      const bool near =
          rule.near_junction <= 0.0 || std::any_of(junctions.begin(), junctions.end(), [&](Vec2 j) {
            return distance_to_segment(j, left, right) <= rule.near_junction;
          });
      if (near) {
        bound = &rule;
        break;
      }
    }
    if (!bound) {
      out.push_back(unbound);
      continue;
    }
    std::vector<std::uint8_t> only(std::size_t(exemplar_count), 0);
    only[std::size_t(bound->exemplar)] = 1;
    out.push_back(std::move(only));
  }
  return out;
}

MixedExemplar mix_exemplars(const std::vector<const Exemplar*>& exemplars, int gap) {
  std::vector<const detail::CostTexels*> costs;
  for (const Exemplar* e : exemplars) costs.push_back(&e->cost);
  detail::ExemplarMix cost_mix = detail::make_exemplar_mix(costs, gap);
  MixedExemplar out;
  out.layout = cost_mix.layout;
  Exemplar& atlas = out.atlas;
  atlas.width = cost_mix.atlas.width;
  atlas.height = cost_mix.atlas.height;
  atlas.cost = std::move(cost_mix.atlas);
  for (const Exemplar* e : exemplars) {
    for (const std::string& name : e->channel_names)
      if (atlas.channel_index(name) < 0) atlas.channel_names.push_back(name);
    atlas.path += (atlas.path.empty() ? "" : " + ") + e->path;
  }
  const int n = atlas.channel_count();
  atlas.texels.assign(std::size_t(atlas.width) * atlas.height * n, 0.0f);
  for (std::size_t k = 0; k < exemplars.size(); ++k) {
    const Exemplar& e = *exemplars[k];
    std::vector<int> to(std::size_t(e.channel_count()));
    for (int c = 0; c < e.channel_count(); ++c)
      to[std::size_t(c)] = atlas.channel_index(e.channel_names[std::size_t(c)]);
    for (int y = 0; y < e.height; ++y)
      for (int x = 0; x < e.width; ++x)
        for (int c = 0; c < e.channel_count(); ++c)
          atlas.texels[(std::size_t(y) * atlas.width + out.layout.x0[k] + x) * n +
                       std::size_t(to[std::size_t(c)])] = e.at(x, y, c);
  }
  return out;
}

Exemplar exemplar_of_mix(const Exemplar& atlas, const MixLayout& layout, int e) {
  if (e < 0 || e >= layout.count()) fail("exemplar {} of a mix of {}", e, layout.count());
  Exemplar out;
  out.width = layout.width[std::size_t(e)];
  out.height = layout.height[std::size_t(e)];
  out.channel_names = atlas.channel_names;
  out.path = atlas.path;
  out.cost.width = out.width;
  out.cost.height = out.height;
  out.cost.binary_alpha = atlas.cost.binary_alpha;
  const std::size_t n = atlas.channel_names.size();
  const std::size_t x0 = std::size_t(layout.x0[std::size_t(e)]);
  for (int y = 0; y < out.height; ++y) {
    const std::size_t row = std::size_t(y) * std::size_t(atlas.width) + x0;
    out.cost.rgba.insert(out.cost.rgba.end(), atlas.cost.rgba.begin() + std::ptrdiff_t(row),
                         atlas.cost.rgba.begin() + std::ptrdiff_t(row + std::size_t(out.width)));
    out.texels.insert(out.texels.end(), atlas.texels.begin() + std::ptrdiff_t(row * n),
                      atlas.texels.begin() + std::ptrdiff_t((row + std::size_t(out.width)) * n));
  }
  return out;
}

}  // namespace tw
