#pragma once
// The per-feature synthesis cache (docs/cache.md). A feature's synthesis is keyed by exactly
// what it reads, in five parts: its geometry and attributes (after conformance), its class's
// synthesis values with the run seed, the canvas cell and the program version, the bytes of the
// exemplar(s) it may use, the avoidance inputs on its canvas (existing features and junction
// discs), and the keys of the features synthesized before it whose canvases overlap its own
// (their opaque coverage is what it avoids; their keys stand for everything they read in turn).
// Entries are content-addressed: <dir>/synthesis/<key>.twc; the last key seen per feature,
// with its parts, lies in <dir>/synthesis/last/ so that a rebuild can say why.
//
// The finer check: the avoidance and earlier parts stand for more than the DP reads (a box
// that meets the canvas, an earlier feature whose coverage moved elsewhere). Each entry also
// records its input hash, of what the DP did read (synthesis_input_hash), and an index
// <dir>/synthesis/inputs/<input key>.twc names the entry by geometry, config, exemplar and that
// hash. A key that misses in its avoidance or earlier part only is looked up there
// (find_by_input) once the avoidance is made: an equal input hash reuses the placements.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/content_hash.hpp"
#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/run.hpp"
#include "raster/avoidance.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/curve.hpp"
#include "synth/feature_synthesis.hpp"
#include "synth/synthesize.hpp"

namespace tw::detail {

struct SynthesisKey {
  ContentHash geometry, config, exemplar, avoidance, earlier;
  ContentHash combined() const;
};

// An earlier feature as a later one's key sees it.
struct EarlierSynthesis {
  GridSpec canvas;
  ContentHash key;
};

// What a cached synthesis gives back: everything the render and the later features need.
struct CachedSynthesis {
  Synthesis synthesis;
  std::size_t exemplar_slot = 0;      // index into the class's exemplars
  std::optional<Curve> start;         // a closed curve's rotated start (start_in_the_clear)
  SparseRaster<std::uint8_t> opaque;  // over the canvas
  FeatureSynthesisReport report;      // as when it was built (timings: 0)
};

// The hash of what a feature's DP reads besides its exemplars and parameters (those are the
// key's config and exemplar parts, its ribbon the geometry part): the forbidden mask on the
// tiles it reads, the closed curve's start, and a mix's junctions.
ContentHash synthesis_input_hash(const FeatureAvoidance& avoidance,
                                 const std::vector<Vec2>& junctions);

class SynthesisCache {
 public:
  // No `dir`: keys are computed (report.json shows them) but nothing is read or written.
  SynthesisCache(std::optional<std::filesystem::path> dir, Warnings& warnings);

  // A mix (choose: mix) adds its bind rules' verdicts on the line (`bindings`, to the geometry
  // part: they are what its attributes say), the junctions it meets (to the avoidance part,
  // beside the junction discs) and its atlas's gap (`atlas_gap`, to the config part: the
  // placements are atlas columns, and the gap follows the class's widest line, not this one).
  SynthesisKey key(const PipelineConfig& config, const FeatureClassConfig& feature_class,
                   const LineFeature& line, std::uint64_t feature_seed, const GridSpec& canvas,
                   const AvoidanceInputs& fixed, const std::vector<EarlierSynthesis>& earlier,
                   const std::vector<PieceBinding>& bindings = {},
                   const std::vector<Vec2>& junctions = {}, int atlas_gap = 0);

  // The entry under `key` for the feature `name` (placements name: class_fid[_part]), or
  // nullopt; `status` says which and why. A corrupt entry is a warning `cache_corrupt`.
  std::optional<CachedSynthesis> find(const std::string& subject, std::int64_t fid,
                                      const std::string& name, const SynthesisKey& key,
                                      CacheStatus& status);
  // After find missed with `status`: whether the miss may go through the finer check (only
  // the avoidance or earlier part changed).
  static bool finer_check_may_reuse(const CacheStatus& status);
  // The finer check: the entry of the same geometry, config and exemplar whose DP read what
  // `input` (synthesis_input_hash) stands for, or nullopt. Reused: `status` says why with the
  // reason find gave ("avoidance changed, mask the same"); else it is left as it was, unless
  // the index record or its entry is corrupt (a warning `cache_corrupt`, "corrupt entry").
  std::optional<CachedSynthesis> find_by_input(const std::string& subject, std::int64_t fid,
                                               const SynthesisKey& key, const ContentHash& input,
                                               CacheStatus& status);
  // Stores a result under `key` with the hash of its DP's input, indexes it by that hash and
  // records it as `name`'s last key (no-op without a dir).
  void store(const std::string& name, const SynthesisKey& key, const ContentHash& input,
             const Synthesis& synthesis, std::size_t exemplar_slot, const Curve* start,
             const SparseRaster<std::uint8_t>& opaque, const FeatureSynthesisReport& report);

  // The exemplar at `path` as the input check remembered it (detail/exemplar_memo.hpp): size
  // and channel names, no texels; nullopt without a dir or when not remembered.
  std::optional<Exemplar> remembered(const std::filesystem::path& path);

 private:
  ContentHash exemplar_hash(const std::filesystem::path& path);
  // The entry at `path` if its meta names `combined` (and `input`, when given); a corrupt one
  // warns and sets `status` to "corrupt entry".
  std::optional<CachedSynthesis> read_entry(const std::filesystem::path& path,
                                            const ContentHash& combined,
                                            const std::optional<ContentHash>& input,
                                            const std::string& subject, std::int64_t fid,
                                            CacheStatus& status);
  void warn_corrupt(const std::string& subject, std::int64_t fid, const std::filesystem::path& path,
                    const std::string& problem, CacheStatus& status);
  std::filesystem::path entry_path(const ContentHash& key) const;
  std::filesystem::path input_path(const SynthesisKey& key, const ContentHash& input) const;
  std::filesystem::path last_path(const std::string& name) const;

  std::optional<std::filesystem::path> dir_;
  Warnings& warnings_;
  std::unique_ptr<CacheFolder> folder_;  // with dir_: locked and written through
  std::map<std::filesystem::path, ContentHash> exemplars_;
};

}  // namespace tw::detail
