#include "pipeline/detail/tile_cache.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <span>
#include <string_view>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/detail/polygons_hash.hpp"
#include "pipeline/synthesis_method.hpp"
#include "pipeline/version.hpp"
#include "raster/footprint.hpp"
#include "raster/window_index.hpp"
#include "terrain/features.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

// 2: the instance heights fact; 3: every writer option in the key (the GeoTIFFs' metadata
// carries the seed: issue #24); 4: EXR codecs and pixel types chosen per layer; 5: the files
// kept whole under tiles/files (hard-linked into the output), the entry holding their digests.
// 6: a feature's planned profiles in part, the samples the tile can read. 7: each file's stat
// facts and when they were taken, for the quick check before reuse.
constexpr std::uint64_t kTileCacheFormat = 7;
constexpr const char* kFilePrefix = "file:";  // a file's "<xxh3-128 hex> <bytes>"
constexpr const char* kFactPrefix = "fact:";  // numbers the run reports about the tile
// Its cache file's "<bytes> <mtime ns> <inode> <device>" (CacheFileStat), by the file's name.
constexpr const char* kStatPrefix = "stat:";
constexpr const char* kStatTime = "stat_time";  // when the facts were taken (ns since the epoch)
// A reused cache file's time is set again (settle_cache_file) only when older than this: pruning
// counts in days, and every new time means the entry's facts are written again.
constexpr std::int64_t kMarkUsedAfterNs = 24LL * 3600 * 1'000'000'000;

void hash_optional(Hasher& h, const std::optional<double>& v) {
  h.boolean(v.has_value()).real(v.value_or(0.0));
}

// A terrain feature's own values; its planned profiles enter each tile's key in part
// (hash_profile_part), with their steps and lengths here.
ContentHash terrain_hash(const TerrainFeature& f,
                         const std::vector<const std::vector<float>*>& profiles,
                         const std::vector<double>& steps) {
  Hasher h;
  h.u64(std::uint64_t(f.kind)).points(f.centerline.points).boolean(f.centerline.closed);
  h.real(f.width).u64(std::uint64_t(f.structure)).i64(f.layer);
  h.real(f.road.max_grade).real(f.road.shoulder_width).real(f.road.falloff).real(f.road.smoothing);
  hash_optional(h, f.road.max_cut);
  hash_optional(h, f.road.max_fill);
  h.real(f.river.depth).real(f.river.bank_width).real(f.river.falloff).real(f.river.min_slope);
  hash_optional(h, f.river.max_carve);
  h.real(f.ridge.height).real(f.ridge.falloff).real(f.ridge.sharpness);
  h.u64(profiles.size());
  for (std::size_t i = 0; i < profiles.size(); ++i) h.u64(profiles[i]->size()).real(steps[i]);
  return h.digest();
}

// The part [t0, t1] of the segment a + t (b - a), t in [0, 1], that lies in `box`
// (Liang-Barsky); false when none does.
bool clip_segment(Vec2 a, Vec2 b, const PieceBox& box, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const Vec2 d = b - a;
  const auto clip = [&](double p, double q) {  // keeps the t with p t <= q
    if (p == 0.0) return q >= 0.0;
    const double r = q / p;
    if (p < 0.0) {
      if (r > t1) return false;
      t0 = std::max(t0, r);
    } else {
      if (r < t0) return false;
      t1 = std::min(t1, r);
    }
    return true;
  };
  return clip(-d.x, a.x - box.lo.x) && clip(d.x, box.hi.x - a.x) && clip(-d.y, a.y - box.lo.y) &&
         clip(d.y, box.hi.y - a.y);
}

// The samples of a planned profile (of terrain plan entry `entry`) that rendering the world box
// `box` can read, hashed with their first index. apply_terrain takes a pixel's value from the
// profile at the arc length of its nearest centreline point (interpolated between two samples),
// and only within the feature's reach (plus half a pixel): so the samples at the arc lengths of
// the centreline's parts within the box grown by the reach and two pixels, two more on each
// side (the arc length is kept as a float there). A closed centreline: every sample. A profile
// graded anew near a junction (a partner moved) leaves the key of a tile away from it alone.
void hash_profile_part(Hasher& h, const TerrainFeature& entry, const std::vector<float>& profile,
                       double step, const PieceBox& box, double pixel) {
  std::size_t first = 0, end = profile.size();
  const std::vector<Vec2>& p = entry.centerline.points;
  if (!entry.centerline.closed && step > 0.0 && !profile.empty()) {
    const PieceBox reach = grown(box, feature_reach(entry) + 2.0 * pixel);
    double lo = INFINITY, hi = -INFINITY, s = 0.0;
    for (std::size_t k = 0; k + 1 < p.size(); ++k) {  // arc lengths as FeatureIndex sums them
      const double length_k = length(p[k + 1] - p[k]);
      double t0 = 0.0, t1 = 0.0;
      if (clip_segment(p[k], p[k + 1], reach, t0, t1)) {
        lo = std::min(lo, s + t0 * length_k);
        hi = std::max(hi, s + t1 * length_k);
      }
      s += length_k;
    }
    if (!(lo <= hi)) {  // no part within reach: no sample is read
      first = end = 0;
    } else {
      first = std::size_t(std::max(0.0, std::floor(lo / step) - 2.0));
      end = std::min(profile.size(), std::size_t(std::max(0.0, std::ceil(hi / step))) + 3);
      first = std::min(first, end);
    }
  }
  h.u64(first).bytes(std::as_bytes(std::span(profile.data() + first, end - first)));
}

// Stages through an OutputFolder and remembers what (the names under `dir`, the staged paths).
class RecordingStager final : public OutputStager {
 public:
  RecordingStager(OutputStager& output, fs::path dir) : output_(output), dir_(std::move(dir)) {}
  fs::path stage(const fs::path& final_path) override {
    fs::path staged = output_.stage(final_path);
    files.push_back(
        {final_path.lexically_normal().lexically_relative(dir_.lexically_normal()), staged});
    return staged;
  }
  std::vector<std::pair<fs::path, fs::path>> files;

 private:
  OutputStager& output_;
  fs::path dir_;
};

std::string digest_text(const FileDigest& digest) {
  return digest.xxh3_128 + " " + std::to_string(digest.bytes);
}

// digest_text's inverse; nullopt for anything else (a malformed entry).
std::optional<FileDigest> parse_digest(const std::string& text) {
  const std::size_t space = text.find(' ');
  if (space != 32 || text.size() == 33 || text.size() > 33 + 20) return std::nullopt;
  const std::string hex = text.substr(0, 32);
  if (hex.find_first_not_of("0123456789abcdef") != std::string::npos) return std::nullopt;
  if (text.find_first_not_of("0123456789", 33) != std::string::npos) return std::nullopt;
  return FileDigest{std::stoull(text.substr(33)), hex};
}

// A tile file's bytes under the cache: tiles/files/<xxh3-128>.twc.
fs::path cache_file_path(const fs::path& dir, const FileDigest& digest) {
  return dir / "tiles" / "files" / (digest.xxh3_128 + ".twc");
}

std::string stat_text(const CacheFileStat& stat) {
  return fmt::format("{} {} {} {}", stat.bytes, stat.mtime_ns, stat.inode, stat.device);
}

// Reads the whole of `text` as one integer; false for anything else.
template <typename Integer>
bool parse_whole(std::string_view text, Integer& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

// The facts recorded for the tile file `name` (stat_text and kStatTime); nullopt when the entry
// holds none or malformed ones: the file is then read through.
std::optional<RecordedStat> recorded_stat(const CacheSections& sections, const std::string& name) {
  const auto text = sections.find(kStatPrefix + name);
  const auto time = sections.find(kStatTime);
  if (text == sections.end() || time == sections.end()) return std::nullopt;
  RecordedStat recorded;
  std::string_view rest = text->second;
  const auto field = [&rest](auto& value) {
    const std::size_t space = rest.find(' ');
    const bool ok = parse_whole(rest.substr(0, space), value);
    rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
    return ok;
  };
  CacheFileStat& stat = recorded.stat;
  if (!field(stat.bytes) || !field(stat.mtime_ns) || !field(stat.inode) || !field(stat.device) ||
      !rest.empty() || !parse_whole(time->second, recorded.recorded_ns))
    return std::nullopt;
  return recorded;
}

}  // namespace

void hash_window(Hasher& h, const Window& w) {
  h.i64(w.col0).i64(w.row0).i64(w.width).i64(w.height);
}

ContentHash ribbon_hash(const Ribbon& r) {
  return Hasher()
      .points(r.centerline.points)
      .boolean(r.centerline.closed)
      .real(r.width)
      .real(r.delta)
      .boolean(r.closed)
      .u64(r.pieces.size())
      .digest();
}

ContentHash TileKey::combined() const {
  return Hasher().text("terraweave.tile").hash(heightfield).hash(features).hash(config).digest();
}

TileCache::TileCache(const WorldPlan& plan, const WriteOptions& output, std::optional<fs::path> dir,
                     Warnings& warnings)
    : plan_(plan), dir_(std::move(dir)), warnings_(warnings) {
  if (dir_) folder_ = std::make_unique<CacheFolder>(*dir_, warnings_);
  Hasher c;
  c.u64(kTileCacheFormat).text(version_line());
  const GridSpec& g = plan.grid;
  c.i64(g.width).i64(g.height).real(g.origin_x).real(g.origin_y).real(g.pixel_width);
  c.real(g.pixel_height).text(plan.crs_wkt);
  hash_optional(c, plan.nodata);
  c.real(plan.render.avoidance_max_distance);
  c.u64(plan.splat_materials.size());
  for (const std::string& m : plan.splat_materials) c.text(m);
  c.u64(plan.terrain_params.precedence.size());
  for (const FeatureKind k : plan.terrain_params.precedence) c.u64(std::uint64_t(k));
  c.boolean(output.exr).boolean(output.geotiff).boolean(output.preview);
  c.u64(std::uint64_t(output.exr_compression))
      .i64(output.exr_zip_level)
      .u64(std::uint64_t(output.exr_pixels));
  // Everything the GeoTIFF writer puts in a file: its encoding and the dataset metadata
  // (TERRAWEAVE_SEED, _PIPELINE, _HEIGHTFIELD, _VERSION).
  const GeoTiffOptions& tiff = output.geotiff_options;
  c.u64(std::uint64_t(tiff.compression)).u64(std::uint64_t(tiff.predictor));
  c.boolean(tiff.cog).boolean(tiff.overviews).u64(tiff.metadata.size());
  for (const auto& [name, value] : tiff.metadata) c.text(name).text(value);
  c.i64(output.preview_max_size);
  config_ = c.digest();

  std::vector<std::vector<const std::vector<float>*>> profiles(plan.terrain_features.size());
  std::vector<std::vector<double>> steps(plan.terrain_features.size());
  for (std::size_t i = 0; i < plan.terrain.features.size(); ++i) {
    profiles[plan.terrain.input_index[i]].push_back(&plan.terrain.profiles[i]);
    steps[plan.terrain.input_index[i]].push_back(plan.terrain.steps[i]);
  }
  for (std::size_t f = 0; f < plan.terrain_features.size(); ++f)
    terrain_.push_back(terrain_hash(plan.terrain_features[f], profiles[f], steps[f]));
  entries_.resize(plan.terrain_features.size());
  for (std::size_t i = 0; i < plan.terrain.features.size(); ++i)
    entries_[plan.terrain.input_index[i]].push_back(i);
  for (const auto& class_ribbons : plan.ribbons)
    for (const Ribbon& r : class_ribbons) ribbons_.push_back(ribbon_hash(r));
  // The methods' item hashes wait for the first tile that meets one of the method's items: a
  // render-tile away from every pattern hashes none (the patterns' placements as JSON text were
  // 1-2 % of a render-tile, issue #23 item 4).
  methods_.resize(plan.methods.size());
}

TileKey TileCache::key(const TileSpec& tile) const {
  const Window& window = tile.halo_window;
  TileKey key;
  Hasher h;
  hash_window(h, window);
  if (const auto& generated = plan_.heights.generated) {
    h.text("generated").real(generated->pixel_size).u64(generated->seed).real(generated->relief);
    h.text(generated->crs).real(generated->feature_size);
  } else {  // a DEM: the window's heights as read (a DEM file changed elsewhere keeps the tile)
    const Raster<float> heights = read_height_window(plan_.heights, plan_.grid, window);
    h.bytes(std::as_bytes(std::span(heights.pixels)));
  }
  key.heightfield = h.digest();

  Hasher f;
  f.text("terrain");
  const PieceBox window_box = world_box(window, plan_.grid);
  const double pixel = std::min(plan_.grid.pixel_width, plan_.grid.pixel_height);
  for (const std::size_t i : items_meeting(plan_.feature_index, window)) {
    f.hash(terrain_[i]);
    for (const std::size_t e : entries_[i])
      hash_profile_part(f, plan_.terrain.features[e], plan_.terrain.profiles[e],
                        plan_.terrain.steps[e], window_box, pixel);
  }
  const Window reach = grow_window(window, avoidance_halo_pixels(plan_), plan_.grid);
  f.text("ribbons");
  for (const std::size_t i : items_meeting(plan_.ribbon_index, reach)) f.hash(ribbons_[i]);
  const PieceBox box = world_box(reach, plan_.grid);
  f.text("existing");
  hash_polygons_meeting(f, plan_.existing.polygons, box);
  for (std::size_t i = 0; i < plan_.existing.lines.size(); ++i) {
    const double width = plan_.existing.line_widths[i];
    if (meets(box, grown(points_box(plan_.existing.lines[i]), width)))
      f.points(plan_.existing.lines[i]).real(width);
  }
  f.text("junctions");
  hash_polygons_meeting(f, plan_.junction_discs, box);
  // A section per method that renders, named after it, in the methods' order.
  for (std::size_t m = 0; m < plan_.methods.size(); ++m) {
    const MethodPlan& entry = plan_.methods[m];
    if (!entry.method->renders()) continue;
    f.text(entry.method->name());
    const std::vector<std::size_t> items = items_meeting(entry.index, window);
    if (!items.empty() && !methods_[m]) methods_[m] = entry.method->item_hashes(plan_, entry);
    for (const std::size_t i : items) f.hash((*methods_[m])[i]);
  }
  key.features = f.digest();

  Hasher c;
  c.hash(config_).i64(tile.index).i64(tile.ix).i64(tile.iy);
  hash_window(c, tile.window);
  key.config = c.digest();
  return key;
}

std::optional<CacheSections> TileCache::find(const std::string& name, const TileKey& key,
                                             CacheStatus& status, int& files_hashed) {
  const ContentHash combined = key.combined();
  status = {false, "no cache", combined.hex()};
  if (!dir_) return std::nullopt;
  fs::path path = *dir_ / "tiles" / (combined.hex() + ".twc");  // or the corrupt file's
  CacheRead read = read_cache_entry(path);
  if (read.state == CacheRead::State::ok) {
    const auto k = read.sections.find("key");
    if (k != read.sections.end() && k->second == combined.hex()) {
      // Every file checked before any is placed: a tile is reused whole or rebuilt whole.
      std::map<std::string, std::pair<fs::path, CacheFileStat>> checked;  // by file name
      bool record = false;  // facts to record again: a file read through, or marked used
      for (const auto& [section, text] : read.sections) {
        if (!section.starts_with(kFilePrefix)) continue;
        const std::string file_name = section.substr(std::strlen(kFilePrefix));
        const std::optional<FileDigest> digest = parse_digest(text);
        if (!digest) {
          read.state = CacheRead::State::corrupt;
          read.problem = "malformed digest of " + file_name;
          break;
        }
        const fs::path file = cache_file_path(*dir_, *digest);
        const CacheFileCheck check =
            check_cache_file(file, *digest, recorded_stat(read.sections, file_name));
        files_hashed += check.hashed;
        if (check.state == CacheRead::State::ok) {
          checked[file_name] = {file, check.stat};
          record |= check.hashed;
          continue;
        }
        read.state = check.state;  // absent: pruned, the tile is "new"
        if (check.state == CacheRead::State::corrupt) {
          path = file;
          read.problem = check.problem;
        }
        break;
      }
      if (read.state == CacheRead::State::ok) {
        // Used now (pruning by age keeps it); a file's time only when a day old.
        const std::int64_t now = cache_clock_ns();
        for (auto& [file_name, checked_file] : checked) {
          auto& [file, stat] = checked_file;
          if (now - stat.mtime_ns <= kMarkUsedAfterNs) continue;
          settle_cache_file(file);
          if (const std::optional<CacheFileStat> settled = stat_cache_file(file)) stat = *settled;
          record = true;
        }
        if (record) {  // the entry written again: its time is now
          for (const auto& [file_name, checked_file] : checked)
            read.sections[kStatPrefix + file_name] = stat_text(checked_file.second);
          read.sections[kStatTime] = std::to_string(cache_clock_ns());
          folder_->write(path, read.sections);
        } else {
          touch_cache_entry(path);
        }
        status.reused = true;
        status.why = "unchanged";
        return std::move(read.sections);
      }
    } else {
      read.state = CacheRead::State::corrupt;
      read.problem = "key mismatch";
    }
  }
  if (read.state == CacheRead::State::corrupt) {
    warnings_.add(
        "cache_corrupt", "tiles." + name, std::nullopt,
        fmt::format("cache entry {} is corrupt ({}): rebuilt", path.string(), read.problem));
    status.why = "corrupt entry";
    return std::nullopt;
  }
  status.why = "new";
  const CacheRead last = read_cache_entry(*dir_ / "tiles" / "last" / (name + ".twc"));
  if (last.state == CacheRead::State::ok && last.sections.count("heightfield") &&
      last.sections.count("features") && last.sections.count("config")) {
    if (last.sections.at("heightfield") != key.heightfield.hex()) {
      status.why = "heightfield changed";
    } else if (last.sections.at("features") != key.features.hex()) {
      status.why = "features changed";
    } else if (last.sections.at("config") != key.config.hex()) {
      status.why = "config changed";
    }
  }
  return std::nullopt;
}

void TileCache::store(const std::string& name, const TileKey& key, const CacheSections& files) {
  const ContentHash combined = key.combined();
  CacheSections sections = files;
  sections["key"] = combined.hex();
  // The kept files' facts, once all are kept (two files of the same bytes are one cache file),
  // their time set out of the racy window first: the next run trusts them unread.
  for (const auto& [section, text] : files) {
    if (!section.starts_with(kFilePrefix)) continue;
    const fs::path file = cache_file_path(*dir_, *parse_digest(text));
    settle_cache_file(file);
    if (const std::optional<CacheFileStat> stat = stat_cache_file(file))
      sections[kStatPrefix + section.substr(std::strlen(kFilePrefix))] = stat_text(*stat);
  }
  sections[kStatTime] = std::to_string(cache_clock_ns());
  folder_->write(*dir_ / "tiles" / (combined.hex() + ".twc"), sections);
  folder_->write(*dir_ / "tiles" / "last" / (name + ".twc"),
                 {{"heightfield", key.heightfield.hex()},
                  {"features", key.features.hex()},
                  {"config", key.config.hex()}});
}

TileCache::Outcome TileCache::render_or_reuse(const TileSpec& tile, OutputStager& output,
                                              const fs::path& output_dir, const Writer& write) {
  const std::string name = tile_file_stem("tile", tile);
  const TileKey key = this->key(tile);
  Outcome outcome;
  if (std::optional<CacheSections> cached = find(name, key, outcome.status, outcome.files_hashed)) {
    for (const auto& [section, bytes] : *cached) {
      if (section.rfind(kFactPrefix, 0) == 0) {
        outcome.facts[section.substr(std::strlen(kFactPrefix))] = bytes;
        continue;
      }
      if (section.rfind(kFilePrefix, 0) != 0) continue;
      const fs::path relative = section.substr(std::strlen(kFilePrefix));
      const FileDigest digest = *parse_digest(bytes);  // checked by find
      const fs::path staged = output.stage(output_dir / relative);
      // A link, not a copy: the cache file is read-only and checked before each reuse.
      std::error_code ignored;
      fs::remove(staged, ignored);
      place_cache_file(cache_file_path(*dir_, digest), staged);
      outcome.staged.push_back({relative, staged});
      outcome.digests[relative] = digest;
    }
    logger().debug("{}: reused from the cache ({}; {} of {} files read for their hash)", name,
                   outcome.status.key, outcome.files_hashed, outcome.staged.size());
    return outcome;
  }
  RecordingStager stager(output, output_dir);
  LayerSet layers = render_tile(plan_, tile);
  write(layers, stager, outcome.facts);
  outcome.staged = stager.files;
  if (dir_) {
    CacheSections sections;
    // Each file read once, for its hash (which the manifest reuses), and kept by a link.
    for (const auto& [file, staged] : stager.files) {
      const FileDigest digest = file_digest(staged);
      folder_->keep_file(cache_file_path(*dir_, digest), staged);
      sections[kFilePrefix + file.generic_string()] = digest_text(digest);
      outcome.digests[file] = digest;
    }
    for (const auto& [fact, value] : outcome.facts) sections[kFactPrefix + fact] = value;
    store(name, key, sections);
  }
  return outcome;
}

}  // namespace tw::detail
