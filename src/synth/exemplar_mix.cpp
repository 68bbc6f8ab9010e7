#include "synth/exemplar_mix.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "synth/detail/exemplar_mix.hpp"
#include "synth/detail/footprint.hpp"

namespace tw {

int MixLayout::exemplar_at(int ux, int uy) const {
  for (std::size_t e = 0; e < x0.size(); ++e)
    if (ux >= x0[e] && ux < x0[e] + width[e]) return uy < height[e] ? int(e) : -1;
  return -1;
}

int mix_gap(const Ribbon& ribbon, double scale) {
  double reach = 1.0;
  for (const Piece& piece : ribbon.pieces) {
    const detail::PieceFrame frame = detail::piece_frame(piece, scale);
    double lo = 0.0, hi = 0.0;
    for (const Vec2& w : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right}) {
      const double x = detail::to_exemplar(frame, w).x;
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    reach = std::max(reach, std::ceil(hi) - std::floor(lo));
  }
  return int(reach) + 4;  // + the bilinear neighbour and a texel of edge rounding each side
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

}  // namespace tw
