#pragma once
// The pattern objective's unary term (docs/synthesis.md, "Objective"): a piece at position u
// pays for the opaque interior texels it holds fewer than a window centred on the pattern's
// band would. Backend-independent: the DP adds it to each row's costs after the pairwise
// update, so every backend keeps the same (exact) row kernel and CPU = OpenCL by construction.
#include <cstdint>
#include <vector>

#include "synth/detail/stages.hpp"

namespace tw::detail {

// The columns [x0, x0 + width) of one exemplar in a mix's atlas (synth/exemplar_mix.hpp) and its
// own band centre, in 1/256 texel.
struct CoverageBand {
  int x0 = 0, width = 0;
  std::int32_t band_centre_fixed = 0;
};

struct CoverageTerm {
  // 0: the paper's objective (no unary term). Else the weight w in thousandths: losing the
  // fraction f of the centred window's opaque texels costs w * f * C * gamma, as much as w * f * C
  // mismatched seam samples.
  std::int32_t weight_milli = 0;
  // The band's centre row in 1/256 texel (ExemplarStats::band_centre): a piece is "centred"
  // when its interior's rows are centred on it.
  std::int32_t band_centre_fixed = 0;
  // A mix: each exemplar's columns and band centre, so that a position pays what it pays in its
  // own exemplar (centred on that exemplar's band, against the mean over its columns). Empty:
  // one band over every column, centred at band_centre_fixed.
  std::vector<CoverageBand> bands;
};

// term.bands, or the one band of all `width` columns.
std::vector<CoverageBand> coverage_bands(const CoverageTerm& term, int width);

// Opaque texels (alpha >= 128) among `piece.interior` at each position of `indices`, from
// per-row prefix sums over the interior's row runs.
void count_opaque_interior(const CostTexels& texels, const PositionSpace& space,
                           const PieceFootprint& piece, const std::vector<std::int32_t>& indices,
                           std::vector<std::int32_t>& counts);

// The centred row uy_c of `piece` (its interior's rows centred on the band).
int centred_row(const PieceFootprint& piece, std::int32_t band_centre_fixed);
inline int centred_row(const PieceFootprint& piece, const CoverageTerm& term) {
  return centred_row(piece, term.band_centre_fixed);
}

// The unary cost of each position of `indices`: with n interior texels, o(u) opaque ones,
// o_c(ux) those of the centred window at the same column and m the mean of o_c over all
// columns (of the band holding ux, in a mix), lost(u) = max(0, max(m, o_c(ux)) - o(u)) and
//   cost(u) = floor(weight_milli * gamma * C * lost(u) / (1000 * n))   (exact integers).
// Both the exemplar-wide mean (no drifting to sparse columns) and the column's own centred
// window (no drifting off the band) are targets. A position in no band costs 0.
void coverage_costs(const CostTexels& texels, const PositionSpace& space,
                    const PieceFootprint& piece, const CoverageTerm& term,
                    const std::vector<std::int32_t>& indices, std::vector<std::int64_t>& costs);

// Mean over columns of the centred window's opaque fraction o_c(ux) / n for `piece`: the
// exemplar's natural coverage at this piece's shape (in a mix, that of the band holding
// column ux; 0 in no band).
double natural_coverage(const CostTexels& texels, const PositionSpace& space,
                        const PieceFootprint& piece, const CoverageTerm& term, int ux = 0);

}  // namespace tw::detail
