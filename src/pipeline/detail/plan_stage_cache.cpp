#include "pipeline/detail/plan_stage_cache.hpp"

#include <gdal_priv.h>

#include <fmt/format.h>

#include "core/log.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/version.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

// 1: the value and its warnings, plan_binary bytes. 2: the ribbons per feature and the latest
// junction search (detail/ribbon_cache.hpp), no longer the ribbons stage whole.
constexpr std::uint64_t kPlanStageCacheFormat = 2;

// Every file GDAL reads for the dataset at `path`: a change to any of them may change the
// heights. Just the path when GDAL cannot open it (the ingest has said why already).
std::vector<std::string> dataset_files(const fs::path& path) {
  std::vector<std::string> files;
  GDALAllRegister();
  if (GDALDatasetH dataset =
          GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)) {
    if (char** list = GDALGetFileList(dataset)) {
      for (char** f = list; *f; ++f) files.emplace_back(*f);
      CSLDestroy(list);
    }
    GDALClose(dataset);
  }
  if (files.empty()) files.push_back(path.string());
  return files;
}

fs::path entry_path(const fs::path& dir, const std::string& stage, const ContentHash& key) {
  return dir / "plan" / stage / (key.hex() + ".twc");
}

}  // namespace

Hasher plan_stage_hasher(const char* stage) {
  Hasher h;
  h.text("terraweave.plan").text(stage).u64(kPlanStageCacheFormat).text(version_line());
  return h;
}

ContentHash heights_identity(const HeightfieldInput& input, const Heightfield& heightfield) {
  Hasher h;
  h.text("terraweave.heights");
  if (input.file) {
    h.text("file").text(to_bytes(input.options));
    const std::vector<std::string> files = dataset_files(*input.file);
    h.u64(files.size());
    for (const std::string& file : files) h.text(file).file(file);
  } else {
    h.text("generated").text(to_bytes(generated_terrain(input)));
  }
  h.text(to_bytes(heightfield.grid)).text(heightfield.crs_wkt);
  h.boolean(heightfield.nodata_value.has_value()).real(heightfield.nodata_value.value_or(0.0));
  return h.digest();
}

ContentHash terrain_plan_key(const ContentHash& heights,
                             const std::vector<TerrainFeature>& features,
                             const TerrainParams& params) {
  return plan_stage_hasher("terrain")
      .hash(heights)
      .text(to_bytes(features))
      .text(to_bytes(params))
      .digest();
}

CachedHeightsAlong::CachedHeightsAlong(const std::optional<fs::path>& dir,
                                       const ContentHash& heights, HeightsAlong sample)
    : sample_(std::move(sample)) {
  if (!dir) return;
  path_ = *dir / "plan" / "heights_along" / (heights.hex() + ".twc");
  // A corrupt entry counts as none (as a remembered exemplar, detail/exemplar_memo.hpp): its
  // centrelines are sampled again and it is replaced. Not a warning: it would be counted among
  // the terrain plan's, and replayed with it.
  CacheRead read = read_cache_entry(*path_);
  if (read.state == CacheRead::State::ok) {
    known_ = std::move(read.sections);
    touch_cache_entry(*path_);
  }
}

HeightsAlong CachedHeightsAlong::reader() {
  return [this](const Curve& centerline, double step) {
    const std::string key =
        Hasher().points(centerline.points).boolean(centerline.closed).real(step).digest().hex();
    std::vector<double> heights;
    if (const auto it = known_.find(key); it != known_.end()) {
      try {
        from_bytes(it->second, heights, "heights along");
        used_[key] = it->second;
        return heights;
      } catch (const Error&) {  // written by another version: sampled again and replaced
        heights.clear();
      }
    }
    heights = sample_(centerline, step);
    used_[key] = to_bytes(heights);
    ++sampled_;
    return heights;
  };
}

void CachedHeightsAlong::store() const {
  if (!path_ || sampled_ == 0) return;
  Warnings unwritable;  // the run's synthesis and tile caches warn about it, once
  CacheFolder folder(path_->parent_path().parent_path().parent_path(), unwritable);
  folder.write(*path_, used_);
}

void warn_corrupt_plan_entry(Warnings& warnings, const std::string& stage, const fs::path& path,
                             const std::string& problem) {
  warnings.add("cache_corrupt", "plan." + stage, std::nullopt,
               fmt::format("cache entry {} is corrupt ({}): rebuilt", path.string(), problem));
}

std::optional<StageEntry> find_stage_entry(const fs::path& dir, const std::string& stage,
                                           const ContentHash& key, Warnings& warnings,
                                           CacheStatus& status) {
  const fs::path path = entry_path(dir, stage, key);
  CacheRead read = read_cache_entry(path);
  status.why = "new";
  if (read.state == CacheRead::State::absent) return std::nullopt;
  if (read.state == CacheRead::State::ok) {
    StageEntry entry;
    try {
      if (read.sections["key"] != key.hex()) fail("key mismatch");
      from_bytes(read.sections["warnings"], entry.warnings, path.string());
      entry.value = std::move(read.sections["value"]);
      touch_cache_entry(path);  // used now: pruning by age keeps it
      status.reused = true;
      status.why = "unchanged";
      logger().debug("{}: reused from the cache ({})", stage, key.hex());
      return entry;
    } catch (const Error& e) {
      read.problem = e.what();
    }
  }
  stage_entry_corrupt(dir, stage, key, read.problem, warnings, status);
  return std::nullopt;
}

void stage_entry_corrupt(const fs::path& dir, const std::string& stage, const ContentHash& key,
                         const std::string& problem, Warnings& warnings, CacheStatus& status) {
  warn_corrupt_plan_entry(warnings, stage, entry_path(dir, stage, key), problem);
  status.reused = false;
  status.why = "corrupt entry";
}

void store_stage_entry(const fs::path& dir, const std::string& stage, const ContentHash& key,
                       const std::string& value, const std::vector<Warning>& warnings) {
  Warnings unwritable;  // the run's synthesis and tile caches warn about it, once
  CacheFolder folder(dir, unwritable);
  folder.write(entry_path(dir, stage, key),
               {{"key", key.hex()}, {"value", value}, {"warnings", to_bytes(warnings)}});
}

}  // namespace tw::detail
