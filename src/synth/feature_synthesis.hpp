#pragma once
// One feature's pattern synthesis on its own canvas (issue #4, docs/patterns.md): the avoidance
// on the canvas (existing features, junction discs, the opaque coverage of the features
// synthesized before it, its own fold-overs), a clear start for a closed curve, the DP over one
// or several exemplars, and the violation check that yields the opaque coverage later features
// avoid. The pipeline orders the features, caches the results and maps its config to these
// options; this is the whole per-feature run.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "raster/avoidance.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/curve.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/backend_kind.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_mix.hpp"
#include "synth/synthesize.hpp"

namespace tw {

enum class ExemplarChoice {
  by_seed,  // each feature uses exemplars[feature seed % count]
  best,     // each feature runs every exemplar and keeps the lowest Omega / N
  mix,      // one DP over all of them (synth/exemplar_mix.hpp): pieces switch where seams match
};

// What one feature's synthesis reports (report.json `synthesis`).
struct FeatureSynthesisReport {
  std::string exemplar;  // the exemplar used (a mix: its paths joined by " + ")
  // choose: mix (empty otherwise): the exemplars in atlas order, the non-empty pieces drawn from
  // each, the seams between pieces of different exemplars and the switching cost, colour units.
  std::vector<std::string> mix_exemplars;
  std::vector<int> pieces_per_exemplar;
  int exemplar_switches = 0;
  int switch_cost = 0;
  std::uint64_t seed = 0;             // the feature's seed: hash(run seed, class seed, FID)
  std::string backend;                // cpu or opencl (what ran)
  double mean_valid_positions = 0.0;  // per piece
  std::int64_t omega = 0;             // optimal cost, cost units
  double mean_seam_cost = 0.0;        // Omega / N in colour units, before stitching
  double mean_seam_cost_stitched = 0.0;
  // Quality (issue #11): the objective and coverage floor used, the chosen windows' coverage
  // against windows centred on the exemplar's band, and parametric texture mapping's mean seam
  // cost on the same ribbon (colour units, like mean_seam_cost).
  std::string objective;
  double min_coverage = 0.0;
  bool min_coverage_from_exemplar = false;
  double coverage_ratio = 0.0, mean_coverage = 0.0, natural_coverage = 0.0;
  double parametric_seam_cost = 0.0;
  // The synthesis ribbon's width and piece length, metres, and where they came from: "config",
  // "exemplar" (issue #11: derived from its statistics) or, for the width, "feature".
  double width_m = 0.0, delta_m = 0.0;
  std::string width_from, delta_from;
  std::int64_t violations = 0;  // opaque canvas pixels on forbidden ones (must be 0)
  int empty_pieces = 0;         // pieces left empty (no valid position: junctions, avoidance)
  int canvas_width = 0, canvas_height = 0;  // the synthesis window, cells
  double avoidance_seconds = 0.0, synthesis_seconds = 0.0, render_seconds = 0.0;
  std::string placements;  // file name under the output folder
};

// The backends of a run, each made on first use (an OpenCL context is costly to create).
class SynthesisBackends {
 public:
  SynthesisBackends();
  ~SynthesisBackends();
  SynthesisBackends(const SynthesisBackends&) = delete;
  SynthesisBackends& operator=(const SynthesisBackends&) = delete;

  detail::Backend& get(BackendKind kind);

 private:
  std::map<BackendKind, std::unique_ptr<detail::Backend>> backends_;
};

// Whether two canvases' boxes share area (touching edges do not): only then does an earlier
// pattern's coverage reach a later canvas.
bool canvases_overlap(const GridSpec& a, const GridSpec& b);

// A pattern synthesized before, as a later feature avoids it: its opaque coverage on its canvas
// (both owned by the caller, alive for the call).
struct EarlierPattern {
  const GridSpec* canvas = nullptr;
  const SparseRaster<std::uint8_t>* opaque = nullptr;
};

struct FeatureSynthesisOptions {
  // The DP's parameters; `seed` is the feature's and `feature_label` (e.g. "features.roads:
  // FID 3") starts every message.
  SynthParams params;
  ExemplarChoice choice = ExemplarChoice::by_seed;
  // The synthesis ribbon's width and delta: a closed curve's ribbon is remade at its clear start.
  RibbonParams ribbon;
  // Cells per side of a canvas tile; 0: one tile for the whole canvas (the same results).
  int canvas_tile = SparseRaster<std::uint8_t>::kDefaultTileSize;
  // Whether a feature none of whose pieces has room is an error. false: it keeps its all-empty
  // placements (nothing rendered, report.empty_pieces == pieces), for the many short lines of
  // a grown class packed between their own joints and other patterns.
  bool no_room_is_error = true;
  // choose: mix. The exemplars' atlas (null: made here with the gap mix_gap(scale, delta,
  // width) of the ribbon), the binding rules in order and the junctions the feature meets
  // (bind_pieces on the synthesized ribbon); params.switch_cost is the switching cost.
  const MixedExemplar* mix = nullptr;
  std::vector<PieceBinding> bindings;
  std::vector<Vec2> junctions;
};

struct FeatureSynthesisResult {
  Ribbon ribbon;                  // what was synthesized: a closed curve's starts in the clear
  std::optional<Curve> start;     // a closed curve's rotated centreline (start_in_the_clear)
  Synthesis synthesis;            // one placement per piece of `ribbon`
  std::size_t exemplar_slot = 0;  // index into `exemplars` (0 for a mix)
  // choose: mix with options.mix null: the atlas made here, which the placements read.
  std::optional<MixedExemplar> mix;
  SparseRaster<std::uint8_t> opaque;  // over the canvas: 1 where the pattern has coverage > 0
  FeatureSynthesisReport report;      // without `placements` (the caller names the file)
};

// What a feature's DP reads besides its exemplars and parameters (the pipeline hashes it to
// reuse a synthesis whose avoidance changed only where the DP does not look: docs/cache.md).
struct FeatureAvoidance {
  Ribbon ribbon;               // as synthesized: a closed curve's starts in the clear
  std::optional<Curve> start;  // a closed curve's rotated centreline (start_in_the_clear)
  // On the canvas tiles the ribbon's pieces read (a halo of a cell beyond them): `fixed`, the
  // overlapping earlier patterns' opaque coverage and the ribbon's own fold-overs.
  SparseRaster<std::uint8_t> forbidden;
  double seconds = 0.0;  // spent making it
};

// The avoidance on `canvas` of `ribbon` (made from `curve`; a closed one is rotated to start in
// the clear, options.ribbon), as synthesize_feature computes it.
FeatureAvoidance feature_avoidance(const Curve& curve, const Ribbon& ribbon, const GridSpec& canvas,
                                   const AvoidanceInputs& fixed,
                                   const std::vector<EarlierPattern>& earlier,
                                   const FeatureSynthesisOptions& options);

// Synthesizes `ribbon` (made from `curve`) on `canvas` (synthesis_canvas) with one of
// `exemplars` (by seed), the best of them or a mix of them all (placements in atlas columns),
// avoiding `fixed` (include_foldovers false), every `earlier` pattern whose canvas overlaps and the
// ribbon's own fold-overs. Throws tw::Error starting with the label when no piece has room (unless
// options.no_room_is_error is false), or when the pattern puts an opaque pixel on a forbidden one
// (a bug).
FeatureSynthesisResult synthesize_feature(SynthesisBackends& backends,
                                          const std::vector<const Exemplar*>& exemplars,
                                          const Curve& curve, const Ribbon& ribbon,
                                          const GridSpec& canvas, const AvoidanceInputs& fixed,
                                          const std::vector<EarlierPattern>& earlier,
                                          const FeatureSynthesisOptions& options);
// The same on an avoidance feature_avoidance made.
FeatureSynthesisResult synthesize_feature(SynthesisBackends& backends,
                                          const std::vector<const Exemplar*>& exemplars,
                                          FeatureAvoidance avoidance, const GridSpec& canvas,
                                          const FeatureSynthesisOptions& options);

}  // namespace tw
