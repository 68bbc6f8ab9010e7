#pragma once
// Stitching (Section 3.2): an alignment DP between the right-edge samples of piece i and the
// left-edge samples of piece i + 1, and the deformation it implies inside piece i.
#include <cstdint>
#include <vector>

#include "ribbon/ribbon.hpp"
#include "synth/synthesize.hpp"

namespace tw::detail {

// M[s][t] = xi(L[s], R[t]) + min(M[s-1][t-1], M[s-1][t] + beta, M[s][t-1] + beta), beta =
// `penalty` (cost units) when L[s] or R[t] has alpha > 0. Backtracked from (C-1, C-1); T[s] is
// the right index of the cheapest cell of row s on the path (lowest t on ties), so
// sum_s xi(L[s], R[T[s]]) <= the unstitched sum_s xi(L[s], R[s]).
std::vector<int> align_edges(const std::uint32_t* right, const std::uint32_t* left, int count,
                             bool binary_alpha, std::int64_t penalty);

// Exemplar coordinates (absolute, continuous texels) of a world point in a piece, with the
// stitching deformation Delta * x / (x + r) along the right edge when `stitched`.
Vec2 placement_to_exemplar(const Placement& placement, const Piece& piece, Vec2 world,
                           bool stitched);

// The same relative to (ux, uy), so floor() of it is exact for texel lookups.
Vec2 placement_to_relative(const Placement& placement, const Piece& piece, Vec2 world,
                           bool stitched);

}  // namespace tw::detail
