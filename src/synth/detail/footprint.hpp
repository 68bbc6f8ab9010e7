#pragma once
// From a ribbon piece in world metres to its exemplar-space footprint (Section 1.3).
// The piece frame M maps a world vector w to exemplar texels s * (dot(w, e_a), dot(w, e_l)):
// e_l = normalized(l) (top -> bottom, exemplar +y), e_a its perpendicular with a positive dot
// with the tangent (exemplar +x). A piece at position u covers, relative to u,
//   (0.5, 0) + M(p - T(x_i))
// so its left edge runs through the centres of exemplar column ux (see docs/synthesis.md).
#include <cstdint>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/detail/stages.hpp"

namespace tw::detail {

struct PieceFrame {
  Vec2 origin;  // T(x_i), world
  Vec2 along;   // e_a, world unit vector -> exemplar +x
  Vec2 across;  // e_l, world unit vector -> exemplar +y
  double scale = 1.0;
};

PieceFrame piece_frame(const Piece& piece, double scale);
// World point -> exemplar coordinates relative to the position u (continuous texels).
Vec2 to_exemplar(const PieceFrame& frame, Vec2 world);
Vec2 to_world(const PieceFrame& frame, Vec2 exemplar);

// C = ceil(s * b): samples per edge.
int column_count(double ribbon_width, double scale);

// Winding number of the piece quad (T, B, B', T') around a point; +1 inside a regular piece,
// -1 inside the inverted lobe of a folded one, 0 outside.
int piece_winding(const Piece& piece, Vec2 world);

// Subsamples per canvas pixel side used by the renderer (and by the avoidance guarantee).
int supersampling(double scale, const GridSpec& canvas);
Vec2 subsample_world(const GridSpec& canvas, int col, int row, int i, int j, int n);

// The opaque interior texels a valid position needs under the floor `min_coverage`: at least one.
int min_opaque_texels(double min_coverage, std::size_t interior);

// The footprint of `piece`. `forbidden` (over `canvas`, non-zero = forbidden) may be null; it
// is read within a pixel of the piece's box.
// `min_coverage` in [0, 1): the fraction of interior texels that must be opaque at a valid
// position (at least one texel whatever the fraction).
PieceFootprint make_piece_footprint(const Piece& piece, double scale, int column,
                                    const GridSpec& canvas,
                                    const SparseRaster<std::uint8_t>* forbidden,
                                    double min_coverage = 0.0);

}  // namespace tw::detail
