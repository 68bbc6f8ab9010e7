#pragma once
// The per-tile render cache (docs/cache.md). A tile's files are keyed by exactly what
// render_tile reads for its window (with the overlap): the heights of the window (the generated
// source's parameters, or the window's values as ingested), the features whose footprint meets
// it — terrain features with the samples of their planned profiles that the window can read (a
// junction partner's grading reaches the tiles near the junction),
// ribbons and existing features and junction discs within the avoidance halo, and the rendered
// patterns (placements, ribbon, exemplar bytes, render options) — and the render and output
// values with the program version. Entries hold the digests of the tile's files, which are kept
// whole, read-only, as <dir>/tiles/files/<xxh3-128>.twc and hard-linked into the output on
// reuse after a check (their stat facts as recorded, else their hash): <dir>/tiles/<key>.twc.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/content_hash.hpp"
#include "core/output_folder.hpp"
#include "core/warnings.hpp"
#include "layers/write.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

struct TileKey {
  ContentHash heightfield, features, config;
  ContentHash combined() const;
};

class TileCache {
 public:
  // Hashes every feature and ribbon of `plan` once, a method's items when a tile first meets one
  // (a tile then hashes their hashes; not thread-safe);
  // `output`: the writer's options the tile's files depend on. No `dir`: keys only.
  TileCache(const WorldPlan& plan, const WriteOptions& output,
            std::optional<std::filesystem::path> dir, Warnings& warnings);

  TileKey key(const TileSpec& tile) const;

  // What render_or_reuse did: the status, the files it staged (name under the output folder ->
  // staged path) and the facts `write` noted about the rendered tile (kept with its files, so a
  // reused tile reports the same numbers), and, with a cache, the digests of its files (hashed
  // once, on storing or on the check before reuse: the manifest need not read them again).
  struct Outcome {
    CacheStatus status;
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged;
    std::map<std::string, std::string> facts;
    std::map<std::filesystem::path, FileDigest> digests;  // by name under the output folder
    // How many of the tile's cache files the check before a reuse read through for their hash
    // (the quick check, their stat facts as recorded, did not vouch for them: docs/cache.md).
    int files_hashed = 0;
  };
  using Writer =
      std::function<void(LayerSet&, OutputStager&, std::map<std::string, std::string>& facts)>;

  // Renders `tile` and has `write` stage its files through the given stager, or, when the cache
  // holds the files under the tile's key, stages hard links to them (the same names, the same
  // bytes; copies across file systems). Stores a rebuilt tile's files (made read-only and linked
  // into the cache) and facts.
  Outcome render_or_reuse(const TileSpec& tile, OutputStager& output,
                          const std::filesystem::path& output_dir, const Writer& write);

 private:
  std::optional<CacheSections> find(const std::string& name, const TileKey& key,
                                    CacheStatus& status, int& files_hashed);
  void store(const std::string& name, const TileKey& key, const CacheSections& files);

  const WorldPlan& plan_;
  std::optional<std::filesystem::path> dir_;
  Warnings& warnings_;
  std::unique_ptr<CacheFolder> folder_;            // with dir_: locked and written through
  ContentHash config_;                             // what every tile shares
  std::vector<ContentHash> terrain_, ribbons_;     // by plan index
  std::vector<std::vector<std::size_t>> entries_;  // terrain plan entries per terrain feature
  // Per plan.methods entry, by item; hashed when a tile first meets one of its items (key()).
  mutable std::vector<std::optional<std::vector<ContentHash>>> methods_;
};

// The parts of a key that the methods' item hashes share (SynthesisMethod::item_hashes).
void hash_window(Hasher& h, const Window& w);
ContentHash ribbon_hash(const Ribbon& r);

}  // namespace tw::detail
