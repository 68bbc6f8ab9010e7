#pragma once
// The parametric texture mapping baseline the paper improves on: the exemplar repeated along
// arc length (u = s x mod W), rows centred across the ribbon, no search. Its placements use the
// same Placement transform, so seam costs compare directly with synthesize().
#include "synth/synthesize.hpp"

namespace tw {

// Placements and Omega / seams (colour units, mean_seam_cost) of the baseline.
Synthesis parametric_baseline(const Exemplar& exemplar, const Ribbon& ribbon, double scale);

}  // namespace tw
