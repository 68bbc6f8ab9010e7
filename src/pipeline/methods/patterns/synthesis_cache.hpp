#pragma once
// The per-feature synthesis cache (docs/cache.md). A feature's synthesis is keyed by exactly
// what it reads, in five parts: its geometry and attributes (after conformance), its class's
// synthesis values with the run seed, the canvas cell and the program version, the bytes of the
// exemplar(s) it may use, the avoidance inputs on its canvas (existing features and junction
// discs), and the keys of the features synthesized before it whose canvases overlap its own
// (their opaque coverage is what it avoids; their keys stand for everything they read in turn).
// Entries are content-addressed: <dir>/synthesis/<key>.twc; the last key seen per feature,
// with its parts, lies in <dir>/synthesis/last/ so that a rebuild can say why.
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

class SynthesisCache {
 public:
  // No `dir`: keys are computed (report.json shows them) but nothing is read or written.
  SynthesisCache(std::optional<std::filesystem::path> dir, Warnings& warnings);

  // A mix (choose: mix) adds its bind rules' verdicts on the line (`bindings`, to the geometry
  // part: they are what its attributes say) and the junctions it meets (to the avoidance part,
  // beside the junction discs).
  SynthesisKey key(const PipelineConfig& config, const FeatureClassConfig& feature_class,
                   const LineFeature& line, std::uint64_t feature_seed, const GridSpec& canvas,
                   const AvoidanceInputs& fixed, const std::vector<EarlierSynthesis>& earlier,
                   const std::vector<PieceBinding>& bindings = {},
                   const std::vector<Vec2>& junctions = {});

  // The entry under `key` for the feature `name` (placements name: class_fid[_part]), or
  // nullopt; `status` says which and why. A corrupt entry is a warning `cache_corrupt`.
  std::optional<CachedSynthesis> find(const std::string& subject, std::int64_t fid,
                                      const std::string& name, const SynthesisKey& key,
                                      CacheStatus& status);
  // Stores a result under `key` and records it as `name`'s last key (no-op without a dir).
  void store(const std::string& name, const SynthesisKey& key, const Synthesis& synthesis,
             std::size_t exemplar_slot, const Curve* start,
             const SparseRaster<std::uint8_t>& opaque, const FeatureSynthesisReport& report);

  // The exemplar at `path` as the input check remembered it (detail/exemplar_memo.hpp): size
  // and channel names, no texels; nullopt without a dir or when not remembered.
  std::optional<Exemplar> remembered(const std::filesystem::path& path);

 private:
  ContentHash exemplar_hash(const std::filesystem::path& path);
  std::filesystem::path entry_path(const ContentHash& key) const;
  std::filesystem::path last_path(const std::string& name) const;

  std::optional<std::filesystem::path> dir_;
  Warnings& warnings_;
  std::unique_ptr<CacheFolder> folder_;  // with dir_: locked and written through
  std::map<std::filesystem::path, ContentHash> exemplars_;
};

}  // namespace tw::detail
