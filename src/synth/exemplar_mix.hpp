#pragma once
// Several exemplars in one feature (issue #11 item 4): the exemplars side by side in one atlas,
// separated by transparent gaps wider than any read of a piece, so that one DP table holds the
// positions of all of them and seams across exemplars use the same xi as within one; a piece
// at an atlas position reads (costs, validity, rendered channels) exactly what it reads at that
// position of its own exemplar. See docs/synthesis.md, "Several exemplars in one feature".
#include <cstdint>
#include <string>
#include <vector>

#include "ribbon/ribbon.hpp"
#include "synth/exemplar.hpp"

namespace tw {

struct MixLayout {
  std::vector<int> x0;             // atlas column of each exemplar's column 0
  std::vector<int> width, height;  // of each exemplar
  int gap = 0;                     // transparent columns between two exemplars
  int count() const { return int(x0.size()); }
  // The exemplar of the atlas texel column ux and row uy, -1 where it is none's (a gap, below
  // a shorter exemplar); positions above an exemplar (uy < 0) are its own.
  int exemplar_at(int ux, int uy) const;
};

struct MixedExemplar {
  Exemplar atlas;  // every channel of every exemplar (a channel one lacks reads 0 there)
  MixLayout layout;
};

// Columns of gap that no piece of a ribbon `width` metres wide sliced every `delta` metres
// reads across at `scale` texels per metre: along e_a, a piece's corners lie within delta +
// width of its top-left corner (an offset curve's chord over one piece, normals turning by at
// most 180 degrees), so its reads span at most 2 s (delta + width) texels, plus the bilinear
// and rounding margins. synthesize() checks the footprints against the layout's gap.
int mix_gap(double scale, double delta, double width);

// A binding rule: the pieces it selects may use only `exemplar`. It selects every piece of a
// line it matches (line_matches: an attribute or tag predicate on the piece's line), and with
// near_junction > 0 only those whose centre segment (left-edge midpoint to right-edge
// midpoint) passes within near_junction metres of a junction.
struct PieceBinding {
  int exemplar = 0;
  bool line_matches = true;
  double near_junction = 0.0;
};

// SynthParams::piece_exemplars for a ribbon: the first rule that selects a piece binds it; a
// piece no rule selects may use the exemplars no rule names (any, when every one is named).
std::vector<std::vector<std::uint8_t>> bind_pieces(const Ribbon& ribbon, int exemplar_count,
                                                   const std::vector<PieceBinding>& rules,
                                                   const std::vector<Vec2>& junctions);

// Throws tw::Error when the list is empty or the exemplars use different alpha modes.
MixedExemplar mix_exemplars(const std::vector<const Exemplar*>& exemplars, int gap);

// Exemplar e of a mix as it lies in the atlas (its texels and cost texels, the atlas's channels):
// what synthesize() reads its own statistics from (band, coverage floor) inside a mix.
Exemplar exemplar_of_mix(const Exemplar& atlas, const MixLayout& layout, int e);

}  // namespace tw
