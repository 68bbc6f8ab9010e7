#pragma once
// Plan stages in the run cache (docs/cache.md, "Plan stages", issue #23 item 2): the terrain
// plan (every feature's profile, read from the heights along it: a generated world computes its
// noise there) was half of a rerun where nothing changed. It is kept under the hash of exactly
// what it reads, with the program version and the entry format; the warnings it gave are kept
// with it and replayed. (The ribbons are kept per feature: detail/ribbon_cache.hpp.)
//   DIR/plan/<stage>/<key>.twc   sections "key", "value" (plan_binary bytes), "warnings"
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/stages.hpp"
#include "terrain/height_ops.hpp"

namespace tw::detail {

// A hasher that begins every plan-stage key: the stage, the entry format, the program version.
Hasher plan_stage_hasher(const char* stage);

// A corrupt entry of the plan's caches: the warning `cache_corrupt`, subject plan.<stage>; the
// caller makes the value again and replaces the entry.
void warn_corrupt_plan_entry(Warnings& warnings, const std::string& stage,
                             const std::filesystem::path& path, const std::string& problem);

// The value of a one-value plan entry (DIR/plan/<stage>/<key>.twc, sections `key` and `value`:
// a ribbon, a line repair), touched as used (pruning by age keeps it); nullopt when there is
// none, or after warn_corrupt_plan_entry when it is corrupt or holds another key.
template <class T>
std::optional<T> read_plan_value(const std::filesystem::path& path, const std::string& key,
                                 const std::string& stage, Warnings& warnings) {
  CacheRead read = read_cache_entry(path);
  if (read.state == CacheRead::State::ok) {
    try {
      if (read.sections["key"] != key) fail("key mismatch");
      T found;
      from_bytes(read.sections["value"], found, path.string());
      touch_cache_entry(path);
      return found;
    } catch (const Error& e) {
      read.state = CacheRead::State::corrupt;
      read.problem = e.what();
    }
  }
  if (read.state == CacheRead::State::corrupt)
    warn_corrupt_plan_entry(warnings, stage, path, read.problem);
  return std::nullopt;
}

// What the heights of a run are, as a key: the generated world's parameters, or the bytes of
// the DEM and of every file GDAL reads with it (.aux.xml, world file, a VRT's sources) with
// the options it is read with; and the grid, CRS and nodata they give.
ContentHash heights_identity(const HeightfieldInput& input, const Heightfield& heightfield);

// The key of the terrain plan of `features` and `params` over the heights `heights`
// (heights_identity).
ContentHash terrain_plan_key(const ContentHash& heights,
                             const std::vector<TerrainFeature>& features,
                             const TerrainParams& params);

// The heights along each feature that a terrain plan read (HeightsAlong), kept per centreline
// and step under the heights' identity (DIR/plan/heights_along/<heights>.twc): when the terrain
// plan is rebuilt (a moved road), only the features whose centreline changed read the heights
// again. The entry is rewritten with the centrelines of the latest plan when one was sampled.
// No cache dir: every centreline is sampled.
class CachedHeightsAlong {
 public:
  CachedHeightsAlong(const std::optional<std::filesystem::path>& dir, const ContentHash& heights,
                     HeightsAlong sample);
  // The HeightsAlong plan_terrain reads through (the cached samples, else `sample`'s).
  HeightsAlong reader();
  // Stores the samples read since construction when any was new (a failed write is silent: the
  // run's other caches warn about the folder).
  void store() const;
  int sampled() const { return sampled_; }  // centrelines sampled, not found

 private:
  std::optional<std::filesystem::path> path_;
  HeightsAlong sample_;
  CacheSections known_;  // <curve key hex> -> samples (plan_binary bytes)
  CacheSections used_;
  int sampled_ = 0;
};

// An entry of a plan stage, found: its value's bytes and the warnings the stage gave.
struct StageEntry {
  std::string value;
  std::vector<Warning> warnings;
};

// The entry of `stage` under `key` in the cache `dir`; nullopt when there is none (status.why
// "new") or it is corrupt (the warning `cache_corrupt`, status.why "corrupt entry").
std::optional<StageEntry> find_stage_entry(const std::filesystem::path& dir,
                                           const std::string& stage, const ContentHash& key,
                                           Warnings& warnings, CacheStatus& status);
// The corrupt-entry warning, for a value that does not decode.
void stage_entry_corrupt(const std::filesystem::path& dir, const std::string& stage,
                         const ContentHash& key, const std::string& problem, Warnings& warnings,
                         CacheStatus& status);
// Stores a computed value and its warnings (a cache that cannot be written is left to the
// run's synthesis and tile caches to warn about).
void store_stage_entry(const std::filesystem::path& dir, const std::string& stage,
                       const ContentHash& key, const std::string& value,
                       const std::vector<Warning>& warnings);

// compute(warnings), or the value of `stage` cached under `key` in `dir` (its warnings added
// to `warnings` as compute would add them); what is computed is stored. No dir: compute.
template <class T, class Compute>
T cached_stage(const std::optional<std::filesystem::path>& dir, const std::string& stage,
               const ContentHash& key, Warnings& warnings, CacheStatus& status, Compute&& compute) {
  status = {false, "no cache", key.hex()};
  if (!dir) return compute(warnings);
  if (std::optional<StageEntry> entry = find_stage_entry(*dir, stage, key, warnings, status)) {
    T value;
    try {
      from_bytes(entry->value, value, stage);
      for (Warning& w : entry->warnings) warnings.add(std::move(w));
      return value;
    } catch (const Error& e) {
      stage_entry_corrupt(*dir, stage, key, e.what(), warnings, status);
    }
  }
  // The stage's warnings are those it adds to the run's (each logged once, as without a cache).
  const std::size_t before = warnings.size();
  T value = compute(warnings);
  const std::vector<Warning> all = warnings.list();
  store_stage_entry(*dir, stage, key, to_bytes(value),
                    std::vector<Warning>(all.begin() + std::ptrdiff_t(before), all.end()));
  return value;
}

}  // namespace tw::detail
