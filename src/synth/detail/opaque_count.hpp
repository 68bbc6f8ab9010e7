#pragma once
// Opaque texels (alpha >= 128) of a piece's interior at a position u: the coverage floor of
// findValid (PieceFootprint::min_opaque) and the pattern objective's unary term
// (coverage_term.hpp) count the same thing, with this one implementation on the CPU. The
// interior is split into runs of texels along rows or along columns, whichever gives fewer
// runs (a piece is about δ·s texels wide and C tall, so columns usually win by 5–8×), and each
// run is one difference of prefix sums. Any split counts every listed offset once, so the
// count is exact whatever the choice.
#include <cstdint>
#include <vector>

#include "synth/detail/stages.hpp"

namespace tw::detail {

// A run of consecutive texels: along a row (dy fixed, dx in [first, last]) or a column (dx
// fixed, dy in [first, last]).
struct TexelRun {
  int fixed = 0, first = 0, last = 0;
};

// The interior as row runs, in listing order (the kernels' split: kernels/valid_positions.cl).
std::vector<TexelRun> row_runs(const std::vector<TexelOffset>& offsets);
// The interior as column runs (offsets sorted by column, then row).
std::vector<TexelRun> column_runs(const std::vector<TexelOffset>& offsets);

class OpaqueCounter {
 public:
  // Prefix sums of the exemplar's opacity along rows and columns; texels outside read as
  // transparent.
  explicit OpaqueCounter(const CostTexels& texels);
  // Prepares the runs of `interior` (kept until the next call).
  void set_interior(const std::vector<TexelOffset>& interior);
  // Opaque texels among the interior at the position (ux, uy).
  std::int32_t count(int ux, int uy) const;

 private:
  std::int32_t row_run(int y, int x0, int x1) const;
  std::int32_t column_run(int x, int y0, int y1) const;

  int width_ = 0, height_ = 0;
  std::vector<std::int32_t> by_row_;     // [y * (W + 1) + x]: opaque texels of row y left of x
  std::vector<std::int32_t> by_column_;  // [x * (H + 1) + y]: of column x above y
  std::vector<TexelRun> runs_;
  bool columns_ = false;
};

}  // namespace tw::detail
