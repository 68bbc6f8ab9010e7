#include "synth/detail/coverage_term.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "synth/detail/cost.hpp"

namespace tw::detail {
namespace {

// Opaque counts of the exemplar's rows as prefix sums: prefix[y * (W + 1) + x] = opaque
// texels of row y left of column x.
struct OpaquePrefix {
  int width = 0, height = 0;
  std::vector<std::int32_t> prefix;

  explicit OpaquePrefix(const CostTexels& t) : width(t.width), height(t.height) {
    prefix.assign(std::size_t(height) * (width + 1), 0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        prefix[std::size_t(y) * (width + 1) + x + 1] =
            prefix[std::size_t(y) * (width + 1) + x] +
            int(is_opaque(t.rgba[std::size_t(y) * width + x]));
  }
  // Opaque texels of row y in columns [x0, x1] (outside the exemplar: transparent).
  std::int32_t run(int y, int x0, int x1) const {
    if (y < 0 || y >= height) return 0;
    x0 = std::max(x0, 0), x1 = std::min(x1, width - 1);
    if (x0 > x1) return 0;
    const std::int32_t* line = prefix.data() + std::size_t(y) * (width + 1);
    return line[x1 + 1] - line[x0];
  }
};

// The interior as row runs {dy, first dx, last dx}, in listing order (duplicates count twice).
std::vector<std::array<int, 3>> interior_runs(const PieceFootprint& piece) {
  std::vector<std::array<int, 3>> runs;
  for (const TexelOffset& o : piece.interior) {
    if (!runs.empty() && runs.back()[0] == o.dy && runs.back()[2] + 1 == o.dx)
      runs.back()[2] = o.dx;
    else
      runs.push_back({o.dy, o.dx, o.dx});
  }
  return runs;
}

std::int32_t count_at(const OpaquePrefix& opaque, const std::vector<std::array<int, 3>>& runs,
                      int ux, int uy) {
  std::int32_t count = 0;
  for (const auto& [dy, first, last] : runs) count += opaque.run(uy + dy, ux + first, ux + last);
  return count;
}

// o_c(ux) for every column of `band`, and their sum.
struct CentredCounts {
  std::vector<std::int32_t> counts;
  std::int64_t sum = 0;
};
CentredCounts centred_counts(const OpaquePrefix& opaque,
                             const std::vector<std::array<int, 3>>& runs,
                             const PieceFootprint& piece, const CoverageBand& band) {
  CentredCounts out;
  out.counts.resize(std::size_t(band.width));
  const int uy = centred_row(piece, band.band_centre_fixed);
  for (int k = 0; k < band.width; ++k) {
    out.counts[std::size_t(k)] = count_at(opaque, runs, band.x0 + k, uy);
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
  const OpaquePrefix opaque(texels);
  const auto runs = interior_runs(piece);
  counts.resize(indices.size());
  for (std::size_t j = 0; j < indices.size(); ++j)
    counts[j] = count_at(opaque, runs, space.ux(indices[j]), space.uy(indices[j]));
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
  const OpaquePrefix opaque(texels);
  const auto runs = interior_runs(piece);
  const std::vector<CoverageBand> bands = coverage_bands(term, space.width);
  std::vector<CentredCounts> centred;
  for (const CoverageBand& band : bands)
    centred.push_back(centred_counts(opaque, runs, piece, band));
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
    const std::int64_t lost = target - W * count_at(opaque, runs, ux, uy);
    if (lost > 0) costs[j] = std::int64_t(scale * lost / (__int128(1000) * W * n));
  }
}

double natural_coverage(const CostTexels& texels, const PositionSpace& space,
                        const PieceFootprint& piece, const CoverageTerm& term, int ux) {
  if (piece.interior.empty()) return 0.0;
  const std::vector<CoverageBand> bands = coverage_bands(term, space.width);
  const int b = band_of(bands, ux);
  if (b < 0) return 0.0;
  const OpaquePrefix opaque(texels);
  const CentredCounts centred =
      centred_counts(opaque, interior_runs(piece), piece, bands[std::size_t(b)]);
  return double(centred.sum) / double(bands[std::size_t(b)].width) / double(piece.interior.size());
}

}  // namespace tw::detail
