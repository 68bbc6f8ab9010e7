#include "synth/baseline.hpp"

#include <cmath>

#include "core/error.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/footprint.hpp"

namespace tw {

Synthesis parametric_baseline(const Exemplar& exemplar, const Ribbon& ribbon, double scale) {
  if (!(scale > 0.0)) fail("baseline scale must be > 0 (got {})", scale);
  const int C = detail::column_count(ribbon.width, scale);
  const detail::PositionSpace space{exemplar.width, exemplar.height, C};
  Synthesis out;
  out.backend = "parametric";
  out.column = C;
  out.closed = ribbon.closed;
  std::vector<detail::PieceFootprint> pieces;
  std::vector<std::int32_t> positions;
  const int uy = (exemplar.height - C) / 2;
  for (const Piece& piece : ribbon.pieces) {
    const auto frame = detail::piece_frame(piece, scale);
    Placement p;
    p.ux = int(std::lround(scale * piece.x0)) % exemplar.width;
    p.uy = uy;
    p.origin = frame.origin;
    p.along = frame.along;
    p.across = frame.across;
    p.scale = scale;
    out.placements.push_back(p);
    pieces.push_back(detail::make_piece_footprint(piece, scale, C, GridSpec{}, nullptr));
    positions.push_back(std::int32_t((p.uy + C) * exemplar.width + p.ux));
  }
  out.total_cost = detail::sequence_cost(exemplar.cost, space, pieces, positions, ribbon.closed);
  const int seams = ribbon.closed ? int(pieces.size()) : int(pieces.size()) - 1;
  out.mean_seam_cost = seams > 0 ? double(out.total_cost) / seams / detail::kColourScale : 0.0;
  out.mean_seam_cost_stitched = out.mean_seam_cost;
  return out;
}

}  // namespace tw
