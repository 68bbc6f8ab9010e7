#include "synth/feature_synthesis.hpp"

#include <algorithm>
#include <chrono>

#include "core/error.hpp"
#include "core/log.hpp"
#include "raster/foldover.hpp"
#include "synth/baseline.hpp"
#include "synth/detail/backend_factory.hpp"
#include "synth/pattern_canvas.hpp"

namespace tw {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The forbidden mask on `tiles` of the canvas: the fixed avoidance and the earlier patterns.
SparseRaster<std::uint8_t> forbidden_on(const std::vector<TileIndex>& tiles, const GridSpec& canvas,
                                        const AvoidanceInputs& fixed,
                                        const std::vector<EarlierPattern>& earlier,
                                        int canvas_tile) {
  SparseRaster<std::uint8_t> forbidden(canvas.width, canvas.height, 0, canvas_tile);
  add_tiles(forbidden, tiles);
  burn_avoidance(fixed, canvas, forbidden);
  for (const EarlierPattern& e : earlier) {
    if (canvases_overlap(*e.canvas, canvas))
      add_on_lattice(*e.opaque, *e.canvas, forbidden, canvas);
  }
  return forbidden;
}

void report_synthesis(const Exemplar& exemplar, const Ribbon& ribbon, const Synthesis& result,
                      double scale, FeatureSynthesisReport& report) {
  double valid = 0.0;
  for (const int v : result.valid_counts) valid += v;
  report.mean_valid_positions =
      result.valid_counts.empty() ? 0.0 : valid / double(result.valid_counts.size());
  report.exemplar = exemplar.path;
  report.backend = result.backend;
  report.omega = result.total_cost;
  report.mean_seam_cost = result.mean_seam_cost;
  report.mean_seam_cost_stitched = result.mean_seam_cost_stitched;
  report.objective = result.objective;
  report.min_coverage = result.min_coverage;
  report.min_coverage_from_exemplar = result.min_coverage_from_exemplar;
  report.coverage_ratio = result.coverage_ratio;
  report.mean_coverage = result.mean_coverage;
  report.natural_coverage = result.natural_coverage;
  report.parametric_seam_cost = parametric_baseline(exemplar, ribbon, scale).mean_seam_cost;
}

// A mix's part of the report; the parametric baseline is that of its best single exemplar.
void report_mix(const std::vector<const Exemplar*>& exemplars, const Ribbon& ribbon,
                const Synthesis& result, const SynthParams& params,
                FeatureSynthesisReport& report) {
  report.mix_exemplars.clear();
  for (const Exemplar* e : exemplars) report.mix_exemplars.push_back(e->path);
  report.pieces_per_exemplar = result.pieces_per_exemplar;
  report.exemplar_switches = result.exemplar_switches;
  report.switch_cost = params.switch_cost;
  for (std::size_t e = 0; e < exemplars.size(); ++e) {
    const double baseline = parametric_baseline(*exemplars[e], ribbon, params.scale).mean_seam_cost;
    report.parametric_seam_cost =
        e == 0 ? baseline : std::min(report.parametric_seam_cost, baseline);
  }
}

}  // namespace

SynthesisBackends::SynthesisBackends() = default;
SynthesisBackends::~SynthesisBackends() = default;

detail::Backend& SynthesisBackends::get(BackendKind kind) {
  auto& slot = backends_[kind];
  if (!slot) slot = detail::make_backend(kind, nullptr);
  return *slot;
}

bool canvases_overlap(const GridSpec& a, const GridSpec& b) {
  const double ax1 = a.origin_x + a.width * a.pixel_width;
  const double bx1 = b.origin_x + b.width * b.pixel_width;
  const double ay0 = a.origin_y - a.height * a.pixel_height;
  const double by0 = b.origin_y - b.height * b.pixel_height;
  return a.origin_x < bx1 && b.origin_x < ax1 && ay0 < b.origin_y && by0 < a.origin_y;
}

FeatureAvoidance feature_avoidance(const Curve& curve, const Ribbon& ribbon, const GridSpec& canvas,
                                   const AvoidanceInputs& fixed,
                                   const std::vector<EarlierPattern>& earlier,
                                   const FeatureSynthesisOptions& options) {
  FeatureAvoidance out;
  out.ribbon = ribbon;
  const auto started = std::chrono::steady_clock::now();
  std::vector<TileIndex> tiles = canvas_tiles(out.ribbon, canvas, options.canvas_tile);
  out.forbidden = forbidden_on(tiles, canvas, fixed, earlier, options.canvas_tile);
  if (curve.closed) {
    out.start = start_in_the_clear(curve, out.ribbon, canvas, out.forbidden);
    out.ribbon = make_ribbon(*out.start, options.ribbon);
    // The rotated ribbon's pieces differ: it may read a tile more.
    std::vector<TileIndex> more = canvas_tiles(out.ribbon, canvas, options.canvas_tile);
    more.erase(std::remove_if(more.begin(), more.end(),
                              [&](TileIndex t) { return out.forbidden.has_tile(t); }),
               more.end());
    if (!more.empty()) {
      tiles.insert(tiles.end(), more.begin(), more.end());
      out.forbidden = forbidden_on(tiles, canvas, fixed, earlier, options.canvas_tile);
    }
  }
  add_foldovers(out.ribbon, canvas, out.forbidden);
  out.seconds = seconds_since(started);
  return out;
}

FeatureSynthesisResult synthesize_feature(SynthesisBackends& backends,
                                          const std::vector<const Exemplar*>& exemplars,
                                          const Curve& curve, const Ribbon& ribbon,
                                          const GridSpec& canvas, const AvoidanceInputs& fixed,
                                          const std::vector<EarlierPattern>& earlier,
                                          const FeatureSynthesisOptions& options) {
  return synthesize_feature(backends, exemplars,
                            feature_avoidance(curve, ribbon, canvas, fixed, earlier, options),
                            canvas, options);
}

FeatureSynthesisResult synthesize_feature(SynthesisBackends& backends,
                                          const std::vector<const Exemplar*>& exemplars,
                                          FeatureAvoidance avoidance, const GridSpec& canvas,
                                          const FeatureSynthesisOptions& options) {
  const SynthParams& params = options.params;
  const std::string& label = params.feature_label;
  FeatureSynthesisResult out;
  FeatureSynthesisReport& report = out.report;
  report.seed = params.seed;
  out.ribbon = std::move(avoidance.ribbon);
  out.start = std::move(avoidance.start);
  const SparseRaster<std::uint8_t>& forbidden = avoidance.forbidden;
  const Ribbon& synthesized = out.ribbon;
  report.avoidance_seconds = avoidance.seconds;

  // Synthesis: by seed one exemplar, every exemplar and the lowest Omega / N, or one DP over
  // the atlas of them all.
  auto started = std::chrono::steady_clock::now();
  const MixedExemplar* mix = options.choice == ExemplarChoice::mix ? options.mix : nullptr;
  if (options.choice == ExemplarChoice::mix) {
    if (!mix) {
      out.mix =
          mix_exemplars(exemplars, mix_gap(params.scale, synthesized.delta, synthesized.width));
      mix = &*out.mix;
    }
    SynthParams mixed = params;
    mixed.mix = mix->layout;
    mixed.piece_exemplars =
        bind_pieces(synthesized, mix->layout.count(), options.bindings, options.junctions);
    out.synthesis = detail::synthesize_on(backends.get(params.backend), mix->atlas, synthesized,
                                          canvas, &forbidden, mixed);
  } else {
    std::vector<std::size_t> candidates;
    if (options.choice == ExemplarChoice::by_seed) {
      candidates = {std::size_t(params.seed % exemplars.size())};
    } else {
      for (std::size_t e = 0; e < exemplars.size(); ++e) candidates.push_back(e);
    }
    bool have = false;
    for (const std::size_t e : candidates) {
      Synthesis result = detail::synthesize_on(backends.get(params.backend), *exemplars[e],
                                               synthesized, canvas, &forbidden, params);
      if (!have || result.mean_seam_cost < out.synthesis.mean_seam_cost) {
        out.synthesis = std::move(result);
        out.exemplar_slot = e;
        have = true;
      }
    }
  }
  const Exemplar& exemplar = mix ? mix->atlas : *exemplars[out.exemplar_slot];
  const Synthesis& result = out.synthesis;
  const auto empty = std::count_if(result.placements.begin(), result.placements.end(),
                                   [](const Placement& p) { return p.empty; });
  const bool no_room = std::size_t(empty) == result.placements.size();
  if (no_room && options.no_room_is_error) {
    const Piece& first = synthesized.pieces.front();
    fail(
        "{}: no room for the pattern: none of the {} pieces has a valid position in {} "
        "(piece 0 at ({:.2f}, {:.2f}); the avoidance map blocks them all)",
        label, synthesized.pieces.size(), exemplar.path, first.top_left.x, first.top_left.y);
  }
  if (no_room)
    logger().info("{}: no room for the pattern: all {} pieces left empty", label,
                  synthesized.pieces.size());
  report.synthesis_seconds = seconds_since(started);

  // The check: opaque pattern pixels on forbidden canvas pixels, by the synthesizer's own
  // criterion; then the opaque coverage that later features avoid.
  started = std::chrono::steady_clock::now();
  PatternCheck check =
      check_pattern(exemplar, synthesized, result, canvas, forbidden, params.stitch);
  out.opaque = std::move(check.opaque);
  report.violations = check.violations;
  if (report.violations != 0) {
    fail("{}: the pattern puts {} opaque pixels on forbidden ones (a synthesis bug)", label,
         report.violations);
  }
  report.render_seconds = seconds_since(started);

  report_synthesis(exemplar, synthesized, result, params.scale, report);
  if (mix) report_mix(exemplars, synthesized, result, params, report);
  report.empty_pieces = int(empty);
  report.canvas_width = canvas.width;
  report.canvas_height = canvas.height;
  logger().info(
      "{}: {} pieces, {:.0f} valid positions per piece, Omega {}, {:.2f} per seam ({:.2f} "
      "stitched), {} empty, {} violations, canvas {}x{} ({} tiles, {:.1f} MB), {:.2f} s",
      label, synthesized.pieces.size(), report.mean_valid_positions, report.omega,
      report.mean_seam_cost, report.mean_seam_cost_stitched, empty, report.violations, canvas.width,
      canvas.height, forbidden.tile_count(), double(forbidden.allocated_bytes()) / 1e6,
      report.avoidance_seconds + report.synthesis_seconds + report.render_seconds);
  return out;
}

}  // namespace tw
