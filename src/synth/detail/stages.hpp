#pragma once
// The stages of one DP row (Zhou et al. 2013, Section 2), as an interface with two
// implementations: the CPU reference (synth/detail/cpu_backend.*) and OpenCL
// (synth/detail/opencl_backend.*, kernels/*.cl). Both must return bit-identical results:
// every cost is an integer and every tie is broken by the lowest position index.
//
// Conventions shared by both backends:
// - The exemplar is W x H texels; texel (x, y) is row y, column x, y growing downwards.
// - A position u = (ux, uy) is the exemplar texel under a piece's top-left corner, with
//   ux in [0, W) and uy in [-C, H): index(u) = (uy + C) * W + ux, U = W * (H + C).
//   Texels outside the exemplar read as transparent black.
// - Colours are packed RGBA8: R | G << 8 | B << 16 | A << 24. For the cost, alpha is binary
//   (A >= 128 is opaque) unless CostTexels::binary_alpha is false. Colours are premultiplied
//   by alpha at load time (synth/exemplar.cpp), so transparent texels are black.
// - Costs, the bilinear fixed-point read and xi are defined in synth/detail/cost.hpp.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace tw::detail {

struct CostTexels {
  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> rgba;  // W * H packed texels
  bool binary_alpha = true;
};

struct PositionSpace {
  int width = 0;   // W
  int height = 0;  // H
  int column = 0;  // C
  std::int64_t count() const { return std::int64_t(width) * (height + column); }
  int ux(std::int64_t index) const { return int(index % width); }
  int uy(std::int64_t index) const { return int(index / width) - column; }
};

struct TexelOffset {
  std::int32_t dx = 0;
  std::int32_t dy = 0;
};

// The exemplar-space shape of one piece relative to its top-left corner u (integer texels
// and fixed-point, so every backend sees the very same numbers).
struct PieceFootprint {
  int column = 0;  // C = samples per edge
  // Right-edge sample k sits at u + (right_fx[k], right_fy[k]) / 256 texels (texel centres at
  // +0.5); it is read bilinearly in fixed point.
  std::vector<std::int32_t> right_fx, right_fy;
  // Texels that must be transparent at a valid position: those crossed by the top and
  // bottom edges, and those that land on forbidden canvas pixels (avoidance, fold-overs).
  std::vector<TexelOffset> must_be_clear;
  // Texels inside the piece: a valid position has at least `min_opaque` opaque texels among
  // them (the paper: 1, "not empty"; more with SynthParams::min_coverage).
  std::vector<TexelOffset> interior;
  int min_opaque = 1;
};

// C samples per valid position, position-major: samples[j * C + k].
struct ColumnSet {
  int column = 0;
  std::vector<std::uint32_t> samples;
  bool binary_alpha = true;  // copied from CostTexels by the extract stages: selects xi
};

// The edges of one DP row: the right edges of `previous_piece` at `previous_indices` (the
// previous row's positions) and the left edges at `indices` (this row's).
struct RowEdges {
  const PieceFootprint* previous_piece = nullptr;
  const std::vector<std::int32_t>* previous_indices = nullptr;
  const std::vector<std::int32_t>* indices = nullptr;
};

// Host time of one dp_row call: waiting for or running the extraction, and the rest.
struct RowTimes {
  double extract_ms = 0, update_ms = 0;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;

  // findValidPositions: flags[index] = 1 where the piece is valid at that position.
  virtual void find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                                    const PieceFootprint& piece,
                                    std::vector<std::uint8_t>& flags) = 0;
  // compactValidPositions: ascending indices of the set flags (a parallel scan on devices).
  virtual void compact_valid_positions(const std::vector<std::uint8_t>& flags,
                                       std::vector<std::int32_t>& indices) = 0;
  // extractColumns: the right-edge samples of `piece` at each position of `indices`.
  virtual void extract_right_columns(const CostTexels& texels, const PositionSpace& space,
                                     const PieceFootprint& piece,
                                     const std::vector<std::int32_t>& indices, ColumnSet& out) = 0;
  // The left-edge samples (an exemplar column of C texels from u downwards).
  virtual void extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                                    const std::vector<std::int32_t>& indices, ColumnSet& out) = 0;
  // computeCostTable + updateTableRow: for every current position j,
  //   cost[j] = min over v of previous_cost[v] + D(right.samples[v], left.samples[j])
  //   argmin[j] = the lowest v reaching it.
  virtual void update_table_row(const std::vector<std::int64_t>& previous_cost,
                                const ColumnSet& right, const ColumnSet& left,
                                std::vector<std::int64_t>& cost,
                                std::vector<std::int32_t>& argmin) = 0;
  // One DP row: extract_right_columns (row.previous_piece at row.previous_indices),
  // extract_left_columns (row.indices) and update_table_row. `next` (null when the following
  // row runs no update) names the edges of the following row, so that a device backend
  // extracts them while this row's update runs; it never changes results. The default runs
  // the three stages in order and ignores `next`.
  virtual void dp_row(const CostTexels& texels, const PositionSpace& space, const RowEdges& row,
                      const RowEdges* next, const std::vector<std::int64_t>& previous_cost,
                      std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
                      RowTimes& times);

 protected:
  ColumnSet row_right_, row_left_;  // the default dp_row's columns, kept between rows
};

inline void Backend::dp_row(const CostTexels& texels, const PositionSpace& space,
                            const RowEdges& row, const RowEdges*,
                            const std::vector<std::int64_t>& previous_cost,
                            std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
                            RowTimes& times) {
  using Clock = std::chrono::steady_clock;
  auto start = Clock::now();
  extract_right_columns(texels, space, *row.previous_piece, *row.previous_indices, row_right_);
  extract_left_columns(texels, space, *row.indices, row_left_);
  auto extracted = Clock::now();
  update_table_row(previous_cost, row_right_, row_left_, cost, argmin);
  times.extract_ms = std::chrono::duration<double, std::milli>(extracted - start).count();
  times.update_ms = std::chrono::duration<double, std::milli>(Clock::now() - extracted).count();
}

}  // namespace tw::detail
