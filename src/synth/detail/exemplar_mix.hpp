#pragma once
// Several exemplars in one feature (issue #11 item 4, a first exact form): the exemplars are
// laid side by side in one atlas, separated by transparent gaps wider than any read of a
// piece, so that the valid positions of all of them form one DP table and seams across
// exemplars are matched with the same xi as within one. Exact: the cost and validity of a
// piece at an atlas position equal those at the same position of its own exemplar (every read
// that leaves an exemplar lands in a gap, the padding below a shorter exemplar or outside the
// atlas: transparent black, as outside the exemplar). Positions that belong to no exemplar
// (in a gap, or below a shorter exemplar's height) are dropped, and each piece may be bound
// to a subset of the exemplars (a stretch: bridge decks, a `surface` tag). A switching cost
// (DpInput::exemplar_switch) may add to the seams between exemplars.
#include <cstdint>
#include <vector>

#include "synth/detail/stages.hpp"
#include "synth/exemplar_mix.hpp"

namespace tw::detail {

struct ExemplarMix {
  CostTexels atlas;
  MixLayout layout;
  PositionSpace space(int column) const { return {atlas.width, atlas.height, column}; }
};

// The widest horizontal reach of the footprints' reads (validity offsets and bilinear right
// samples), as the transparent gap the atlas needs between exemplars.
int mix_gap(const std::vector<PieceFootprint>& pieces);

// Throws tw::Error when the list is empty or binary_alpha differs between exemplars.
ExemplarMix make_exemplar_mix(const std::vector<const CostTexels*>& exemplars, int gap);

// The exemplar of an atlas position, -1 where it is none's.
int exemplar_of(const MixLayout& layout, const PositionSpace& space, std::int32_t index);

// Keeps the positions of `indices` whose exemplar e has allowed[e] != 0 (empty: any exemplar).
void keep_exemplars(const MixLayout& layout, const PositionSpace& space,
                    const std::vector<std::uint8_t>& allowed, std::vector<std::int32_t>& indices);

// Keeps the positions of `indices` (of exemplars, valid under the lowest floor) whose interior
// holds their own exemplar's coverage floor, floors[e] (SynthParams::min_coverage per exemplar):
// validity in a mix is validity in the position's own exemplar.
void keep_own_coverage_floors(const CostTexels& atlas, const MixLayout& layout,
                              const PositionSpace& space, const PieceFootprint& piece,
                              const std::vector<double>& floors,
                              std::vector<std::int32_t>& indices);

}  // namespace tw::detail
