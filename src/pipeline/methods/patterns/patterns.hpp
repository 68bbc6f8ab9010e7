#pragma once
// The synthesis stage of a run (issue #4, docs/patterns.md): every feature of a class with
// `synthesis` gets a pattern synthesized on its own canvas in world metres (cells of
// `synthesis_resolution`, on a lattice fixed in world coordinates, windowed to the feature),
// avoiding existing features, junction discs, its own fold-overs and the opaque coverage of the
// features synthesized before it; then the patterns are rendered into the output grid.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/content_hash.hpp"
#include "core/grid.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/run.hpp"
#include "raster/sparse_raster.hpp"
#include "synth/exemplar.hpp"
#include "synth/synthesize.hpp"
#include "terrain/splat.hpp"

namespace tw::detail {

// Loads an exemplar and, when NAME_height.tif lies beside NAME.png, its height channel.
Exemplar load_exemplar_with_height(const std::filesystem::path& path, bool continuous_alpha);

// exemplars[index], its texels read first when `unread` lists it (then no longer).
const Exemplar& read_texels(std::deque<Exemplar>& exemplars, std::map<std::size_t, bool>& unread,
                            std::size_t index);

class SynthesisCache;

struct FeaturePattern {
  std::string name;                // placements/<name>.json: <class>_<fid>[_<part>]
  std::size_t class_index = 0;     // in config.features
  std::size_t feature_index = 0;   // in the class's lines / ribbons
  std::size_t exemplar_index = 0;  // in PatternRun::exemplars
  bool on_ground = true;           // false for a bridge or tunnel: not written into the layers
  Ribbon ribbon;                   // the synthesis ribbon (synthesis.width, or the feature's)
  Synthesis synthesis;
  GridSpec canvas;                    // synthesis_canvas (synth/pattern_canvas.hpp)
  SparseRaster<std::uint8_t> opaque;  // over canvas: 1 where the rendered pattern has coverage > 0
  FeatureSynthesisReport report;
  ContentHash key;  // of everything the synthesis read (synthesis_cache.hpp)
  CacheStatus cache;
  // The features before it (synthesis order, counting features with pieces) whose canvases
  // overlap its own: it avoids their coverage, so it depends on them.
  std::vector<std::size_t> after;
  // false: left out by PatternOptions::wanted (ribbon, canvas and indices only).
  bool synthesized = true;
};

struct PatternRun {
  std::deque<Exemplar> exemplars;
  // Exemplars known by size and channels only (remembered by the run cache, while every
  // synthesis using them comes from it): index -> continuous_alpha. read_texels loads one.
  std::map<std::size_t, bool> unread;
  std::vector<FeaturePattern> patterns;  // in synthesis order
};

struct PatternOptions {
  std::optional<std::string> backend;  // replaces every class's backend (RunOptions::backend)
  // Cells per side of a canvas tile; 0: one tile for the whole canvas (the dense canvas, for
  // tests: the same results).
  int canvas_tile = SparseRaster<std::uint8_t>::kDefaultTileSize;
  // Reuses and stores syntheses (`--cache`); null: every feature is synthesized (keys are still
  // computed for the report).
  SynthesisCache* cache = nullptr;
  // Which features are synthesized (distributed synthesis, pipeline/synthesis_job.hpp), by
  // their index in synthesis order among the features with pieces:
  //   all     every feature (the cache's entries reused): a run;
  //   keys    none: names, canvases, keys, `after` and cache statuses only (the task list);
  //   one     the feature `feature`, always synthesized and stored in the cache, which must hold
  //           the features in `after` it depends on (the others are skipped; so are later ones);
  //   cached  every feature from the cache, which must hold them all (a plan's completion).
  enum class Scope { all, keys, one, cached };
  Scope scope = Scope::all;
  std::size_t feature = 0;
  std::vector<std::size_t> after;  // scope one: the features that `feature` depends on
  // Scope one: `feature`'s cache status as the plan found it (syntheses.json). A miss in its
  // avoidance or earlier part only goes through the finer check, as in a run: the task reuses
  // the stored placements whose DP read the same (pattern.cache then says so).
  CacheStatus planned;
  // Synthesizes only the features whose canvas it accepts, and the earlier ones whose canvases
  // overlap theirs (transitively: what their avoidance reads), so each has the placements of a
  // run of every feature (a `region`). Null: every feature.
  std::function<bool(const GridSpec& canvas)> wanted;
};

// Throws tw::Error naming the class and FID (and the piece) of a feature without room for its
// pattern, or when a pattern puts an opaque pixel on a forbidden one (a bug).
PatternRun synthesize_patterns(const PipelineConfig& config,
                               const std::vector<std::vector<LineFeature>>& lines,
                               const FeatureRibbons& ribbons, const ExistingFeatures& existing,
                               const PatternOptions& options = {});

}  // namespace tw::detail
