#pragma once
// Several exemplars in one feature (issue #11 item 4): the exemplars side by side in one atlas,
// separated by transparent gaps wider than any read of a piece, so that one DP table holds the
// positions of all of them and seams across exemplars use the same xi as within one; a piece
// at an atlas position reads (costs, validity, rendered channels) exactly what it reads at that
// position of its own exemplar. See docs/synthesis.md, "Several exemplars in one feature".
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

// Columns of gap that the pieces of `ribbon` at `scale` never read across (their exemplar-space
// extent along x, plus the bilinear and edge margins).
int mix_gap(const Ribbon& ribbon, double scale);

// Throws tw::Error when the list is empty or the exemplars use different alpha modes.
MixedExemplar mix_exemplars(const std::vector<const Exemplar*>& exemplars, int gap);

}  // namespace tw
