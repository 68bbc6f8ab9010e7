// synthesize() on a given backend: footprints, the DP, placements, seam costs, stitching.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.hpp"
#include "raster/footprint.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/coverage_term.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/exemplar_mix.hpp"
#include "synth/detail/foldover.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/stitch.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/synthesize.hpp"

namespace tw::detail {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<std::uint32_t> right_samples(const CostTexels& texels, const PieceFootprint& piece,
                                         int ux, int uy) {
  std::vector<std::uint32_t> out;
  for (int k = 0; k < piece.column; ++k)
    out.push_back(sample_bilinear(texels, ux * 256 - 128 + piece.right_fx[k],
                                  uy * 256 - 128 + piece.right_fy[k]));
  return out;
}

std::vector<std::uint32_t> left_samples(const CostTexels& texels, int C, int ux, int uy) {
  std::vector<std::uint32_t> out;
  for (int k = 0; k < C; ++k) out.push_back(texel_at(texels, ux, uy + k));
  return out;
}

// Does the stitched mapping of piece i keep every forbidden subsample on transparent texels?
bool stitch_respects_avoidance(const CostTexels& texels, const Placement& placement,
                               const Piece& piece, const GridSpec& canvas,
                               const SparseRaster<std::uint8_t>& avoidance, int n) {
  const PieceBox box = piece_pixel_box(piece, canvas);
  const double min_x = box.lo.x, min_y = box.lo.y, max_x = box.hi.x, max_y = box.hi.y;
  for (int row = std::max(0, int(min_y) - 1); row <= std::min(canvas.height - 1, int(max_y) + 1);
       ++row) {
    for (int col = std::max(0, int(min_x) - 1); col <= std::min(canvas.width - 1, int(max_x) + 1);
         ++col) {
      if (!avoidance.at(col, row)) continue;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const Vec2 w = subsample_world(canvas, col, row, i, j, n);
          if (piece_winding(piece, w) == 0) continue;
          const Vec2 q = placement_to_relative(placement, piece, w, true);
          const int x0 = int(std::floor(q.x - 0.5)) + placement.ux;
          const int y0 = int(std::floor(q.y - 0.5)) + placement.uy;
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
              if (is_opaque(texel_at(texels, x0 + dx, y0 + dy))) return false;
        }
      }
    }
  }
  return true;
}

// The unary costs of the chosen positions (0 under the paper's objective).
std::int64_t unary_sum(const CostTexels& texels, const PositionSpace& space, const DpInput& input,
                       const std::vector<std::int32_t>& positions) {
  std::int64_t sum = 0;
  std::vector<std::int64_t> cost;
  for (std::size_t i = 0; i < positions.size() && input.coverage.weight_milli > 0; ++i) {
    if (positions[i] < 0) continue;
    coverage_costs(texels, space, input.pieces[i], input.coverage, {positions[i]}, cost);
    sum += cost[0];
  }
  return sum;
}

// Mean window coverage of the chosen positions against windows centred on the band (each
// piece's own exemplar's band in a mix).
void measure_coverage(const CostTexels& texels, const PositionSpace& space, const DpInput& input,
                      const std::vector<std::int32_t>& positions, const CoverageTerm& centred,
                      Synthesis& out) {
  double chosen = 0.0, natural = 0.0;
  int counted = 0;
  std::vector<std::int32_t> count;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const PieceFootprint& piece = input.pieces[i];
    if (positions[i] < 0 || piece.interior.empty()) continue;
    count_opaque_interior(texels, space, piece, {positions[i]}, count);
    chosen += double(count[0]) / double(piece.interior.size());
    natural += natural_coverage(texels, space, piece, centred, space.ux(positions[i]));
    ++counted;
  }
  if (counted == 0) return;
  out.mean_coverage = chosen / counted;
  out.natural_coverage = natural / counted;
  out.coverage_ratio = natural > 0.0 ? chosen / natural : 0.0;
}

// What the exemplar implies for its synthesis: its statistics and coverage floor, or in a mix
// those of each exemplar as it is alone (exemplar_of_mix), so that a position's validity and
// coverage cost are those it has in its own exemplar and the mix stays exact.
struct OwnStatistics {
  std::vector<ExemplarStats> stats;  // per exemplar of the mix (one without a mix)
  std::vector<double> floors;        // the coverage floor (min_coverage) of each
};

OwnStatistics own_statistics(const Exemplar& exemplar, const SynthParams& params, int C) {
  OwnStatistics out;
  const int count = params.mix ? params.mix->count() : 1;
  for (int e = 0; e < count; ++e) {
    const Exemplar part = params.mix ? exemplar_of_mix(exemplar, *params.mix, e) : Exemplar{};
    const Exemplar& own = params.mix ? part : exemplar;
    out.stats.push_back(exemplar_stats(own));
    out.floors.push_back(params.min_coverage < 0.0
                             ? kCoverageFloorOfNatural * window_coverage(own, out.stats.back(), C)
                             : params.min_coverage);
  }
  return out;
}

std::int32_t fixed_row(double row) {
  return std::int32_t(std::lround(row * 256.0));
}

// Windows centred on the band: the exemplar's, or each mixed exemplar's own over its columns.
CoverageTerm centring(const OwnStatistics& own, const SynthParams& params) {
  CoverageTerm term;
  term.band_centre_fixed = fixed_row(own.stats[0].band_centre);
  for (int e = 0; params.mix && e < params.mix->count(); ++e) {
    term.bands.push_back({params.mix->x0[std::size_t(e)], params.mix->width[std::size_t(e)],
                          fixed_row(own.stats[std::size_t(e)].band_centre)});
  }
  return term;
}

// A mix: positions of no exemplar are dropped, each piece keeps its allowed exemplars' and the
// switching cost joins the objective.
void bind_to_exemplars(const SynthParams& params, const std::string& feature,
                       const std::vector<double>& floors, Synthesis& out, DpInput& input) {
  const MixLayout& layout = *params.mix;
  const int needed = mix_gap(input.pieces);
  if (needed > layout.gap)
    fail("{}: the exemplar mix's gaps of {} columns are narrower than the pieces' reach ({})",
         feature, layout.gap, needed);
  if (!params.piece_exemplars.empty() && params.piece_exemplars.size() != input.pieces.size())
    fail("{}: {} exemplar bindings for {} pieces", feature, params.piece_exemplars.size(),
         input.pieces.size());
  if (params.switch_cost < 0)
    fail("synthesis switch_cost must be >= 0 (got {})", params.switch_cost);
  out.mix = layout;
  const PositionSpace space = input.space;
  input.keep_positions = [&params, space, floors, texels = input.texels, pieces = &input.pieces](
                             int piece, std::vector<std::int32_t>& indices) {
    static const std::vector<std::uint8_t> any;
    const auto& allowed =
        params.piece_exemplars.empty() ? any : params.piece_exemplars[std::size_t(piece)];
    keep_exemplars(*params.mix, space, allowed, indices);
    keep_own_coverage_floors(*texels, *params.mix, space, (*pieces)[std::size_t(piece)], floors,
                             indices);
  };
  input.exemplar_switch.cost = std::int64_t(params.switch_cost) * kColourScale;
  input.exemplar_switch.exemplar = [&params, space](std::int32_t index) {
    return exemplar_of(*params.mix, space, index);
  };
}

}  // namespace

Synthesis synthesize_on(Backend& backend, const Exemplar& exemplar, const Ribbon& ribbon,
                        const GridSpec& canvas, const SparseRaster<std::uint8_t>* forbidden,
                        const SynthParams& params) {
  const auto start = Clock::now();
  if (!(params.scale > 0.0) || !std::isfinite(params.scale))
    fail("synthesis scale s must be > 0 exemplar texels per metre (got {})", params.scale);
  if (ribbon.pieces.empty()) fail("ribbon of {} has no pieces", params.feature_label);
  if (!(params.min_coverage < 1.0))
    fail("synthesis min_coverage must be in [0, 1) (got {})", params.min_coverage);
  if (!(params.coverage_weight >= 0.0 && params.coverage_weight <= 1000.0))
    fail("synthesis coverage_weight must be in [0, 1000] (got {})", params.coverage_weight);
  const std::string feature = params.feature_label.empty() ? "the curve" : params.feature_label;
  const int N = int(ribbon.pieces.size());
  const int C = column_count(ribbon.width, params.scale);
  const CostTexels& texels = exemplar.cost;
  const PositionSpace space{exemplar.width, exemplar.height, C};

  const OwnStatistics own = own_statistics(exemplar, params, C);
  const CoverageTerm centred = centring(own, params);
  Synthesis out;
  out.objective = params.objective == Objective::paper ? "paper" : "pattern";
  out.min_coverage_from_exemplar = params.min_coverage < 0.0;
  // The footprints hold the lowest floor; a mix keeps each position to its own exemplar's.
  out.min_coverage = *std::min_element(own.floors.begin(), own.floors.end());
  out.backend = backend.name();
  out.column = C;
  out.closed = ribbon.closed;
  const SparseRaster<std::uint8_t> avoidance = combined_avoidance(ribbon, canvas, forbidden);
  DpInput input;
  input.texels = &texels;
  input.space = space;
  input.pieces.resize(std::size_t(N));
  tbb::parallel_for(0, N, [&](int i) {
    input.pieces[std::size_t(i)] = make_piece_footprint(ribbon.pieces[std::size_t(i)], params.scale,
                                                        C, canvas, &avoidance, out.min_coverage);
  });
  if (params.objective == Objective::pattern) {
    input.coverage = centred;
    input.coverage.weight_milli = std::int32_t(std::lround(params.coverage_weight * 1000.0));
  }
  out.timings.footprints_ms = ms_since(start);
  input.closed = ribbon.closed;
  input.exact_cycle = params.closed_mode == ClosedMode::exact;
  input.seed = params.seed;
  input.allow_empty = params.allow_empty_pieces;
  input.label = params.feature_label;
  if (params.first_position) {
    const auto [ux, uy] = *params.first_position;
    if (ux < 0 || ux >= space.width || uy < -C || uy >= space.height)
      fail("first_position ({}, {}) is outside the positions [0, {}) x [{}, {}) of exemplar {}", ux,
           uy, space.width, -C, space.height, exemplar.path);
    input.first_index = std::int32_t((uy + C) * space.width + ux);
  }
  input.no_valid_message = [&](int i) {
    const Piece& piece = ribbon.pieces[std::size_t(i)];
    const Vec2 at = lerp(piece.top_left, piece.bottom_right, 0.5);
    std::vector<std::uint8_t> flags;
    backend.find_valid_positions(
        texels, space,
        make_piece_footprint(piece, params.scale, C, canvas, nullptr, out.min_coverage), flags);
    std::vector<std::int32_t> candidates;
    for (std::size_t k = 0; k < flags.size(); ++k)
      if (flags[k]) candidates.push_back(std::int32_t(k));
    // A mix: only the positions of the piece's exemplars, at their own floors.
    if (input.keep_positions) input.keep_positions(i, candidates);
    const std::int64_t without = std::int64_t(candidates.size());
    const std::string reason =
        without > 0 ? fmt::format(
                          "avoidance (forbidden pixels or fold-overs) blocks all {} "
                          "positions that are valid without it",
                          without)
                    : fmt::format(
                          "no position{} where the top and bottom edges clear the "
                          "pattern{}: ribbon width {} m x s = {} texels, exemplar {}x{}",
                          params.mix ? " of the exemplars it may use" : "",
                          out.min_coverage > 0.0
                              ? fmt::format(" with min_coverage {:.3f}", out.min_coverage)
                              : std::string(),
                          ribbon.width, C, exemplar.width, exemplar.height);
    return fmt::format("piece {} of {} at ({:.2f}, {:.2f}): no valid position in exemplar {} ({})",
                       i, feature, at.x, at.y, exemplar.path, reason);
  };

  if (params.mix) bind_to_exemplars(params, feature, own.floors, out, input);

  const DpResult dp = run_dp(backend, input);
  out.objective_cost = dp.total_cost;
  out.total_cost = dp.total_cost;
  out.approximate_cycle_cost = dp.approximate_cycle_cost;
  out.valid_counts = dp.valid_counts;
  out.timings.find_valid_ms = dp.timings.find_valid_ms;
  out.timings.compact_ms = dp.timings.compact_ms;
  out.timings.extract_ms = dp.timings.extract_ms;
  out.timings.update_ms = dp.timings.update_ms;
  out.timings.backtrack_ms = dp.timings.backtrack_ms;
  out.timings.rows = dp.timings.rows;

  for (int i = 0; i < N; ++i) {
    const PieceFrame frame = piece_frame(ribbon.pieces[std::size_t(i)], params.scale);
    Placement p;
    const std::int32_t index = dp.positions[std::size_t(i)];
    p.empty = index < 0;
    p.ux = p.empty ? 0 : space.ux(index);
    p.uy = p.empty ? 0 : space.uy(index);
    p.exemplar = p.empty || !params.mix ? 0 : params.mix->exemplar_at(p.ux, p.uy);
    p.origin = frame.origin;
    p.along = frame.along;
    p.across = frame.across;
    p.scale = params.scale;
    out.placements.push_back(std::move(p));
  }

  if (params.mix) {
    out.pieces_per_exemplar.assign(std::size_t(params.mix->count()), 0);
    for (const Placement& p : out.placements)
      if (!p.empty) ++out.pieces_per_exemplar[std::size_t(p.exemplar)];
    out.exemplar_switches = exemplar_switches(dp.positions, ribbon.closed, [&](std::int32_t i) {
      return exemplar_of(*params.mix, space, i);
    });
    out.total_cost -= std::int64_t(params.switch_cost) * kColourScale * out.exemplar_switches;
  }
  measure_coverage(texels, space, input, dp.positions, centred, out);
  out.total_cost -= unary_sum(texels, space, input, dp.positions);

  // Seams, their costs before and after stitching.
  const auto stitch_start = Clock::now();
  const int seams = ribbon.closed ? N : N - 1;
  const int n = supersampling(params.scale, canvas);
  std::int64_t raw = 0, stitched = 0;
  int counted = 0;
  for (int i = 0; i < seams; ++i) {
    Placement& a = out.placements[std::size_t(i)];
    const Placement& b = out.placements[std::size_t((i + 1) % N)];
    if (a.empty || b.empty) continue;
    const auto R = right_samples(texels, input.pieces[std::size_t(i)], a.ux, a.uy);
    const auto L = left_samples(texels, C, b.ux, b.uy);
    const std::int64_t seam = edge_cost(R.data(), L.data(), C, texels.binary_alpha);
    raw += seam;
    ++counted;
    if (!params.stitch) {
      stitched += seam;
      continue;
    }
    const auto T = align_edges(R.data(), L.data(), C, texels.binary_alpha,
                               std::int64_t(params.stitch_penalty) * kColourScale);
    a.stitch.assign(T.begin(), T.end());
    // The deformation must not move forbidden subsamples onto opaque texels.
    if (!stitch_respects_avoidance(texels, a, ribbon.pieces[std::size_t(i)], canvas, avoidance,
                                   n)) {
      a.stitch.clear();
      stitched += seam;
      continue;
    }
    for (int s = 0; s < C; ++s) stitched += xi(R[std::size_t(T[s])], L[s], texels.binary_alpha);
  }
  out.timings.stitch_ms = ms_since(stitch_start);
  out.mean_seam_cost = counted ? double(raw) / counted / kColourScale : 0.0;
  out.mean_seam_cost_stitched = counted ? double(stitched) / counted / kColourScale : 0.0;
  out.timings.total_ms = ms_since(start);
  return out;
}

}  // namespace tw::detail
