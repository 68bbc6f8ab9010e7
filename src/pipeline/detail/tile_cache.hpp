#pragma once
// The per-tile render cache (docs/cache.md). A tile's files are keyed by exactly what
// render_tile reads for its window (with the overlap): the heights of the window (the generated
// source's parameters, or the window's values as ingested), the features whose footprint meets
// it — terrain features with their planned profiles (a junction partner's profile included),
// ribbons and existing features and junction discs within the avoidance halo, and the rendered
// patterns (placements, ribbon, exemplar bytes, render options) — and the render and output
// values with the program version. Entries hold the tile's file bytes: <dir>/tiles/<key>.twc.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/content_hash.hpp"
#include "core/output_folder.hpp"
#include "core/warnings.hpp"
#include "pipeline/cache_status.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

struct TileKey {
  ContentHash heightfield, features, config;
  ContentHash combined() const;
};

// What a tile's files depend on besides the plan: the writer's choices.
struct TileOutputValues {
  bool exr = true;
  bool geotiff = true;
};

// A file written for a tile: its name relative to the output folder, and where it was staged.
struct StagedTileFile {
  std::filesystem::path name;
  std::filesystem::path staged;
};

class TileCache {
 public:
  // Hashes every feature, ribbon and pattern of `plan` once (a tile then hashes their hashes).
  // No `dir`: keys only.
  TileCache(const WorldPlan& plan, TileOutputValues output,
            std::optional<std::filesystem::path> dir, Warnings& warnings);

  TileKey key(const TileSpec& tile) const;

  // Renders `tile` and stages its files with `write` (which returns what it staged), or, when
  // the cache holds the files under the tile's key, stages copies of them. Returns the status.
  CacheStatus render_or_reuse(
      const TileSpec& tile, OutputFolder& output, const std::filesystem::path& output_dir,
      const std::function<std::vector<StagedTileFile>(const LayerSet&)>& write);

 private:
  std::optional<CacheSections> find(const std::string& name, const TileKey& key,
                                    CacheStatus& status);
  void store(const std::string& name, const TileKey& key, const CacheSections& files);

  const WorldPlan& plan_;
  TileOutputValues output_;
  std::optional<std::filesystem::path> dir_;
  Warnings& warnings_;
  ContentHash config_;                                     // what every tile shares
  std::vector<ContentHash> terrain_, ribbons_, patterns_;  // by plan index
};

}  // namespace tw::detail
