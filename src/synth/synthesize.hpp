#pragma once
// Pattern synthesis along a ribbon (Zhou, Lasram & Lefebvre 2013): each piece of the ribbon
// gets a position in the exemplar, chosen by an exact DP over all valid positions so that the
// colours across consecutive piece edges match best (Omega); then optional stitching.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/backend_kind.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_mix.hpp"

namespace tw {

class OpenCLContext;  // synth/opencl_context.hpp
namespace detail {
class Backend;  // synth/detail/stages.hpp
}

enum class ClosedMode {
  approximate,  // the paper's single DP, backtracked from every terminal position
  exact,        // one DP per start position, pruned by the single DP's terminal costs
};

enum class Objective {
  paper,    // Omega alone (Zhou et al. 2013): the optimum may copy fringes or stray texels
  pattern,  // Omega + a unary coverage term: the optimum is a centred copy (docs/synthesis.md)
};

struct SynthParams {
  double scale = 0.0;      // s: exemplar texels per metre (the paper's s is our s * b)
  std::uint64_t seed = 0;  // 0: global optimum; else piece 0 is drawn among its valid positions
  bool stitch = true;      // Section 3.2 edge alignment
  BackendKind backend = BackendKind::cpu;
  ClosedMode closed_mode = ClosedMode::approximate;
  bool allow_empty_pieces = false;  // a piece without valid position stays empty (penalized)
  // The fraction of a piece's interior texels that must be opaque at a valid position, in
  // [0, 1). 0 is the paper's "not empty" (one texel); more keeps the optimum from choosing
  // nearly empty pieces whose transparent edges seam for free.
  // Negative: from the exemplar, kCoverageFloorOfNatural x the natural coverage of a window
  // of C rows centred on its band (synth/exemplar_stats.hpp).
  double min_coverage = -1.0;
  Objective objective = Objective::pattern;
  // Pattern objective: losing the fraction f of a centred window's opaque texels costs as much
  // as coverage_weight * f * C mismatched seam samples (coverage_weight * f * C * gamma).
  double coverage_weight = 2.0;
  std::optional<std::pair<int, int>> first_position;  // fixes piece 0 at (ux, uy)
  int stitch_penalty = 32;                            // the paper's P, in 0..255 colour units
  std::string feature_label;  // names the feature in messages, e.g. "feature 42"
  // Several exemplars in one feature: the exemplar is the atlas of mix_exemplars with this
  // layout. switch_cost (colour units, as the seam costs; 0: none) is added to every seam
  // between pieces of different exemplars; piece_exemplars[i][e] != 0 allows piece i to use
  // exemplar e (an empty list, or an empty entry: any exemplar).
  std::optional<MixLayout> mix;
  int switch_cost = 0;
  std::vector<std::vector<std::uint8_t>> piece_exemplars;
};

// Where one piece reads the exemplar: exemplar = (ux + 0.5, uy) + s * (dot(p - origin, along),
// dot(p - origin, across)) for a world point p, plus the stitching deformation.
struct Placement {
  int ux = 0, uy = 0;  // position of the top-left corner (uy may be negative, down to -C)
  int exemplar = 0;    // in a mix: the exemplar of the position (ux is an atlas column)
  bool empty = false;  // no valid position (allow_empty_pieces): renders transparent
  Vec2 origin;         // T(x_i), world metres
  Vec2 along;          // e_a: world unit vector mapped to exemplar +x
  Vec2 across;         // e_l: world unit vector mapped to exemplar +y (top -> bottom)
  double scale = 1.0;  // s
  // The paper's T: right-edge sample index shown at right-edge sample k (empty: identity).
  std::vector<float> stitch;
};

struct SynthTimings {
  double footprints_ms = 0, find_valid_ms = 0, compact_ms = 0, extract_ms = 0, update_ms = 0,
         backtrack_ms = 0, stitch_ms = 0, total_ms = 0;
  int rows = 0;
};

struct Synthesis {
  std::vector<Placement> placements;  // one per ribbon piece
  std::int64_t total_cost = 0;        // Omega in cost units (xi = 16 x colour distance)
  // What the DP minimized: Omega + the pattern objective's unary costs (+ empty penalties).
  std::int64_t objective_cost = 0;
  // Omega per seam in colour units (xi / 16), before and after stitching.
  double mean_seam_cost = 0.0;
  double mean_seam_cost_stitched = 0.0;
  std::int64_t approximate_cycle_cost = -1;  // closed curves: the single-DP cycle (-1: none)
  std::vector<int> valid_counts;             // valid positions per piece
  int column = 0;                            // C
  bool closed = false;
  std::string backend;
  SynthTimings timings;
  // The objective and coverage floor used (min_coverage_from_exemplar: the floor was derived).
  std::string objective;
  double min_coverage = 0.0;
  bool min_coverage_from_exemplar = false;
  // Mean opaque fraction of the chosen windows (non-empty pieces) and of windows centred on the
  // exemplar's band, of the same pieces; coverage_ratio = mean_coverage / natural_coverage.
  double mean_coverage = 0.0, natural_coverage = 0.0, coverage_ratio = 0.0;
  // A mix: its layout, the non-empty pieces drawn from each exemplar and the seams between
  // pieces of different exemplars.
  std::optional<MixLayout> mix;
  std::vector<int> pieces_per_exemplar;
  int exemplar_switches = 0;
};

// `forbidden` (may be null): the avoidance map over `canvas`, non-zero = forbidden; it must hold
// every tile within a pixel or two of a piece (ribbon_tiles with a halo of 2), absent tiles read
// as free.
Synthesis synthesize(const Exemplar& exemplar, const Ribbon& ribbon, const GridSpec& canvas,
                     const SparseRaster<std::uint8_t>* forbidden, const SynthParams& params,
                     OpenCLContext* context = nullptr);

namespace detail {
// The same on a given backend.
Synthesis synthesize_on(Backend& backend, const Exemplar& exemplar, const Ribbon& ribbon,
                        const GridSpec& canvas, const SparseRaster<std::uint8_t>* forbidden,
                        const SynthParams& params);
}  // namespace detail

}  // namespace tw
