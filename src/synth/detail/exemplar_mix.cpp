#include "synth/detail/exemplar_mix.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "synth/detail/coverage_term.hpp"
#include "synth/detail/footprint.hpp"

namespace tw::detail {

int mix_gap(const std::vector<PieceFootprint>& pieces) {
  int right = 1, left = 0;  // left edges read dx = 0 only
  for (const PieceFootprint& p : pieces) {
    for (const auto* offsets : {&p.must_be_clear, &p.interior})
      for (const TexelOffset& o : *offsets)
        right = std::max(right, o.dx), left = std::min(left, o.dx);
    for (std::int32_t fx : p.right_fx) {
      const int x = (fx - 128) >> 8;  // the bilinear read touches x and x + 1
      right = std::max(right, x + 1);
      left = std::min(left, x);
    }
  }
  return right - left + 1;
}

ExemplarMix make_exemplar_mix(const std::vector<const CostTexels*>& exemplars, int gap) {
  if (exemplars.empty()) fail("an exemplar mix needs at least one exemplar");
  ExemplarMix mix;
  mix.atlas.binary_alpha = exemplars[0]->binary_alpha;
  int width = 0, height = 0;
  for (std::size_t e = 0; e < exemplars.size(); ++e) {
    const CostTexels& t = *exemplars[e];
    if (t.binary_alpha != mix.atlas.binary_alpha)
      fail("exemplar {} of the mix uses another alpha mode than exemplar 0", e);
    mix.layout.x0.push_back(width);
    mix.layout.width.push_back(t.width);
    mix.layout.height.push_back(t.height);
    width += t.width + (e + 1 < exemplars.size() ? std::max(gap, 1) : 0);
    height = std::max(height, t.height);
  }
  mix.layout.gap = std::max(gap, 1);
  mix.atlas.width = width;
  mix.atlas.height = height;
  mix.atlas.rgba.assign(std::size_t(width) * height, 0u);
  for (std::size_t e = 0; e < exemplars.size(); ++e) {
    const CostTexels& t = *exemplars[e];
    for (int y = 0; y < t.height; ++y)
      std::copy_n(t.rgba.data() + std::size_t(y) * t.width, t.width,
                  mix.atlas.rgba.data() + std::size_t(y) * width + mix.layout.x0[e]);
  }
  return mix;
}

int exemplar_of(const MixLayout& layout, const PositionSpace& space, std::int32_t index) {
  return layout.exemplar_at(space.ux(index), space.uy(index));
}

void keep_exemplars(const MixLayout& layout, const PositionSpace& space,
                    const std::vector<std::uint8_t>& allowed, std::vector<std::int32_t>& indices) {
  std::erase_if(indices, [&](std::int32_t index) {
    const int e = exemplar_of(layout, space, index);
    return e < 0 || (!allowed.empty() && !allowed[std::size_t(e)]);
  });
}

void keep_own_coverage_floors(const CostTexels& atlas, const MixLayout& layout,
                              const PositionSpace& space, const PieceFootprint& piece,
                              const std::vector<double>& floors,
                              std::vector<std::int32_t>& indices) {
  std::vector<int> needed;
  for (const double floor : floors)
    needed.push_back(min_opaque_texels(floor, piece.interior.size()));
  // The valid positions hold piece.min_opaque already (the lowest floor).
  if (std::all_of(needed.begin(), needed.end(), [&](int n) { return n <= piece.min_opaque; }))
    return;
  std::vector<std::int32_t> counts;
  count_opaque_interior(atlas, space, piece, indices, counts);
  std::size_t kept = 0;
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const int e = exemplar_of(layout, space, indices[j]);
    if (e >= 0 && counts[j] >= needed[std::size_t(e)]) indices[kept++] = indices[j];
  }
  indices.resize(kept);
}

}  // namespace tw::detail
