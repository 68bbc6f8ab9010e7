#include "synth/detail/coverage_term.hpp"

#include <algorithm>
#include <cmath>

#include "synth/detail/cost.hpp"
#include "synth/detail/opaque_count.hpp"

namespace tw::detail {
namespace {

// o_c(ux) for every column of `band`, and their sum.
struct CentredCounts {
  std::vector<std::int32_t> counts;
  std::int64_t sum = 0;
};
// `opaque` holds the piece's interior.
CentredCounts centred_counts(const OpaqueCounter& opaque, const PieceFootprint& piece,
                             const CoverageBand& band) {
  CentredCounts out;
  out.counts.resize(std::size_t(band.width));
  const int uy = centred_row(piece, band.band_centre_fixed);
  for (int k = 0; k < band.width; ++k) {
    out.counts[std::size_t(k)] = opaque.count(band.x0 + k, uy);
    out.sum += out.counts[std::size_t(k)];
  }
  return out;
}

// The band holding column ux, -1 for none.
int band_of(const std::vector<CoverageBand>& bands, int ux) {
  for (std::size_t b = 0; b < bands.size(); ++b)
    if (ux >= bands[b].x0 && ux < bands[b].x0 + bands[b].width) return int(b);
  return -1;
}

}  // namespace

void count_opaque_interior(const CostTexels& texels, const PositionSpace& space,
                           const PieceFootprint& piece, const std::vector<std::int32_t>& indices,
                           std::vector<std::int32_t>& counts) {
  OpaqueCounter opaque(texels);
  opaque.set_interior(piece.interior);
  counts.resize(indices.size());
  for (std::size_t j = 0; j < indices.size(); ++j)
    counts[j] = opaque.count(space.ux(indices[j]), space.uy(indices[j]));
}

std::vector<CoverageBand> coverage_bands(const CoverageTerm& term, int width) {
  if (!term.bands.empty()) return term.bands;
  return {{0, width, term.band_centre_fixed}};
}

int centred_row(const PieceFootprint& piece, std::int32_t band_centre_fixed) {
  if (piece.interior.empty()) return 0;
  int dy0 = piece.interior.front().dy, dy1 = dy0;
  for (const TexelOffset& o : piece.interior) dy0 = std::min(dy0, o.dy), dy1 = std::max(dy1, o.dy);
  // uy_c + (dy0 + dy1 + 1) / 2 = band centre, rounded to the nearest row (in fixed point).
  const std::int32_t offset = band_centre_fixed - (dy0 + dy1 + 1) * 128;
  return int(std::floor((offset + 128) / 256.0));
}

void coverage_costs(const CostTexels& texels, const PositionSpace& space,
                    const PieceFootprint& piece, const CoverageTerm& term,
                    const std::vector<std::int32_t>& indices, std::vector<std::int64_t>& costs) {
  costs.assign(indices.size(), 0);
  const std::int64_t n = std::int64_t(piece.interior.size());
  if (term.weight_milli <= 0 || n == 0) return;
  OpaqueCounter opaque(texels);
  opaque.set_interior(piece.interior);
  const std::vector<CoverageBand> bands = coverage_bands(term, space.width);
  std::vector<CentredCounts> centred;
  for (const CoverageBand& band : bands) centred.push_back(centred_counts(opaque, piece, band));
  // Per band of W columns, in units of 1 / W texel: target(ux) = max(sum, W * o_c(ux)),
  // lost = target - W * o(u).
  const __int128 scale = __int128(term.weight_milli) * kGamma * piece.column;
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const int ux = space.ux(indices[j]), uy = space.uy(indices[j]);
    const int b = band_of(bands, ux);
    if (b < 0) continue;
    const std::int64_t W = bands[std::size_t(b)].width;
    const CentredCounts& c = centred[std::size_t(b)];
    const std::int64_t target =
        std::max(c.sum, W * c.counts[std::size_t(ux - bands[std::size_t(b)].x0)]);
    const std::int64_t lost = target - W * opaque.count(ux, uy);
    if (lost > 0) costs[j] = std::int64_t(scale * lost / (__int128(1000) * W * n));
  }
}

double natural_coverage(const CostTexels& texels, const PositionSpace& space,
                        const PieceFootprint& piece, const CoverageTerm& term, int ux) {
  if (piece.interior.empty()) return 0.0;
  const std::vector<CoverageBand> bands = coverage_bands(term, space.width);
  const int b = band_of(bands, ux);
  if (b < 0) return 0.0;
  OpaqueCounter opaque(texels);
  opaque.set_interior(piece.interior);
  const CentredCounts centred = centred_counts(opaque, piece, bands[std::size_t(b)]);
  return double(centred.sum) / double(bands[std::size_t(b)].width) / double(piece.interior.size());
}

}  // namespace tw::detail
