#pragma once
// The DP over piece positions (Sections 1.4, 1.5 and 2): the row loop findValid / compact /
// extractColumns / updateTableRow on a Backend, then backtracking. Memory is O(N * V): per row
// only the valid indices and the argmins are kept, never a U x U table.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "synth/detail/coverage_term.hpp"
#include "synth/detail/stages.hpp"

namespace tw::detail {

// Exemplar mixes (synth/detail/exemplar_mix.hpp): a cost added to every seam between pieces
// from different exemplars, D'(v, j) = D(v, j) + cost * [exemplar(v) != exemplar(j)]. It is
// pairwise but depends on the exemplars only, so the DP adds it to the previous row's costs
// per exemplar of the current row and D itself (with its pruning bounds) is untouched.
struct ExemplarSwitch {
  std::int64_t cost = 0;                      // in cost units (xi); 0: none
  std::function<int(std::int32_t)> exemplar;  // of a position index
  bool active() const { return cost > 0 && exemplar != nullptr; }
  std::int64_t between(std::int32_t a, std::int32_t b) const {
    return active() && exemplar(a) != exemplar(b) ? cost : 0;
  }
};

struct DpInput {
  const CostTexels* texels = nullptr;
  PositionSpace space;
  std::vector<PieceFootprint> pieces;       // N pieces, in order along the curve
  bool closed = false;                      // add the terminal piece (= piece 0) and keep cycles
  bool exact_cycle = false;                 // closed: one DP per start (pruned) instead of one DP
  std::optional<std::int32_t> first_index;  // fixes piece 0 (must be a valid position)
  std::uint64_t seed = 0;    // != 0 and no first_index: piece 0 drawn among its valid positions
  bool allow_empty = false;  // a row with no valid position becomes an empty piece
  // Drops valid positions of a piece before the DP (exemplar mixes bind pieces to exemplars,
  // synth/detail/exemplar_mix.hpp); keeps the order. Empty: every valid position.
  std::function<void(int piece, std::vector<std::int32_t>& indices)> keep_positions;
  // Message of the tw::Error for a piece without any valid position.
  std::function<std::string(int piece)> no_valid_message;
  std::string label;  // names the feature in progress lines, e.g. "features.roads: FID 3"
  // The pattern objective's unary term (weight 0: the paper's objective, Omega alone).
  CoverageTerm coverage;
  ExemplarSwitch exemplar_switch;
};

struct DpTimings {
  double find_valid_ms = 0, compact_ms = 0, extract_ms = 0, update_ms = 0, backtrack_ms = 0;
  int rows = 0;  // updateTableRow calls
};

struct DpResult {
  std::vector<std::int32_t> positions;  // per piece: position index, -1 for an empty piece
  std::int64_t total_cost = 0;          // Omega + unary costs (+ empty penalties)
  std::vector<int> valid_counts;        // per piece
  // Closed curves: the single-DP approximation's cycle cost (-1 if it found no cycle) and the
  // number of DP passes the exact mode ran (each over a set of start positions).
  std::int64_t approximate_cycle_cost = -1;
  int exact_dp_passes = 0;
  DpTimings timings;
};

// An empty piece costs as much as an edge of C mismatched samples (on both of its edges).
std::int64_t empty_piece_penalty(int column);

DpResult run_dp(Backend& backend, const DpInput& input);

// Omega of a given sequence of positions (no -1), with the same sampling as the DP; closed
// curves include the edge from the last piece back to the first.
std::int64_t sequence_cost(const CostTexels& texels, const PositionSpace& space,
                           const std::vector<PieceFootprint>& pieces,
                           const std::vector<std::int32_t>& positions, bool closed);
// The DP's objective of a sequence: sequence_cost plus every piece's unary coverage cost and
// every seam's switching cost.
std::int64_t objective_cost(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<PieceFootprint>& pieces,
                            const std::vector<std::int32_t>& positions, bool closed,
                            const CoverageTerm& coverage, const ExemplarSwitch& change = {});
// The seams of a sequence (no -1) whose two pieces come from different exemplars.
int exemplar_switches(const std::vector<std::int32_t>& positions, bool closed,
                      const std::function<int(std::int32_t)>& exemplar);
// D between piece i at position a (its right edge) and the next piece at position b.
std::int64_t seam_cost(const CostTexels& texels, const PositionSpace& space,
                       const PieceFootprint& piece, std::int32_t a, std::int32_t b);

}  // namespace tw::detail
