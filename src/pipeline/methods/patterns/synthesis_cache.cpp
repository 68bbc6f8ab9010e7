#include "pipeline/methods/patterns/synthesis_cache.hpp"

#include <algorithm>
#include <span>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/detail/exemplar_memo.hpp"
#include "pipeline/detail/piece_length.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/polygons_hash.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/version.hpp"
#include "raster/footprint.hpp"
#include "synth/feature_synthesis.hpp"
#include "synth/placements_io.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Bumped whenever an entry's layout or meaning changes: old entries then miss. 2: the whole
// report (coverage, objective, ...) in a section of its own (issue #24: a reused synthesis
// reported zeros). 3: the input hash in the meta, and the index by it (the finer check).
constexpr std::uint64_t kSynthesisCacheFormat = 3;

// The reasons the finer check can overrule: nothing the DP reads need have changed.
constexpr const char* kFinerCheckWhys[] = {"avoidance changed", "earlier feature changed"};

std::string encode_opaque(const SparseRaster<std::uint8_t>& opaque) {
  std::string out;
  const auto u64 = [&](std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(char(v >> (8 * i)));
  };
  u64(std::uint64_t(opaque.width()));
  u64(std::uint64_t(opaque.height()));
  u64(std::uint64_t(opaque.tile_size()));
  u64(opaque.tile_count());
  for (const TileIndex t : opaque.tiles()) {
    u64(std::uint64_t(t.tx));
    u64(std::uint64_t(t.ty));
    const Raster<std::uint8_t>& cells = *opaque.tile(t);
    out.append(reinterpret_cast<const char*>(cells.pixels.data()), cells.pixels.size());
  }
  return out;
}

// Throws tw::Error on bytes that do not describe a raster over `canvas`.
SparseRaster<std::uint8_t> decode_opaque(const std::string& in, const GridSpec& canvas) {
  std::size_t at = 0;
  const auto u64 = [&]() {
    if (in.size() - at < 8) fail("opaque: truncated");
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | std::uint8_t(in[at + std::size_t(i)]);
    at += 8;
    return v;
  };
  const std::uint64_t width = u64(), height = u64(), tile = u64(), count = u64();
  if (width != std::uint64_t(canvas.width) || height != std::uint64_t(canvas.height) || tile == 0 ||
      tile > (1u << 30)) {
    fail("opaque: {}x{} (tiles {}) does not fit the canvas", width, height, tile);
  }
  SparseRaster<std::uint8_t> opaque(int(width), int(height), 0, int(tile));
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint64_t tx = u64(), ty = u64();
    if (tx >= std::uint64_t(opaque.tiles_x()) || ty >= std::uint64_t(opaque.tiles_y()))
      fail("opaque: tile ({}, {}) outside", tx, ty);
    Raster<std::uint8_t>& cells = opaque.add_tile({int(tx), int(ty)});
    if (in.size() - at < cells.pixels.size()) fail("opaque: truncated tile");
    std::copy_n(in.begin() + std::ptrdiff_t(at), cells.pixels.size(), cells.pixels.begin());
    at += cells.pixels.size();
  }
  if (at != in.size()) fail("opaque: {} trailing bytes", in.size() - at);
  return opaque;
}

std::string encode_parts(const SynthesisKey& k) {
  return json{{"geometry", k.geometry.hex()}, {"config", k.config.hex()},
              {"exemplar", k.exemplar.hex()}, {"avoidance", k.avoidance.hex()},
              {"earlier", k.earlier.hex()},   {"key", k.combined().hex()}}
      .dump();
}

// The first part that differs, in the order in which they are listed to the user.
std::string why_changed(const SynthesisKey& now, const json& before) {
  const std::pair<const char*, const ContentHash*> parts[] = {{"geometry", &now.geometry},
                                                              {"config", &now.config},
                                                              {"exemplar", &now.exemplar},
                                                              {"avoidance", &now.avoidance},
                                                              {"earlier", &now.earlier}};
  for (const auto& [name, hash] : parts) {
    if (before.at(name).get<std::string>() == hash->hex()) continue;
    return std::string(name) == "earlier" ? "earlier feature changed"
                                          : std::string(name) + " changed";
  }
  return "new";  // the same parts: the entry was pruned
}

}  // namespace

ContentHash synthesis_input_hash(const FeatureAvoidance& avoidance,
                                 const std::vector<Vec2>& junctions) {
  const SparseRaster<std::uint8_t>& forbidden = avoidance.forbidden;
  std::vector<TileIndex> tiles = forbidden.tiles();  // canonical: row-major
  std::sort(tiles.begin(), tiles.end(),
            [](TileIndex a, TileIndex b) { return std::pair(a.ty, a.tx) < std::pair(b.ty, b.tx); });
  Hasher h;
  h.text("terraweave.synthesis.input");
  h.u64(std::uint64_t(forbidden.width()))
      .u64(std::uint64_t(forbidden.height()))
      .u64(std::uint64_t(forbidden.tile_size()))
      .u64(tiles.size());
  for (const TileIndex t : tiles) {
    const std::vector<std::uint8_t>& cells = forbidden.tile(t)->pixels;
    h.i64(t.tx).i64(t.ty).bytes(std::as_bytes(std::span(cells)));
  }
  h.boolean(avoidance.start.has_value());
  if (avoidance.start) h.points(avoidance.start->points);
  h.points(junctions);
  return h.digest();
}

ContentHash SynthesisKey::combined() const {
  return Hasher()
      .text("terraweave.synthesis")
      .hash(geometry)
      .hash(config)
      .hash(exemplar)
      .hash(avoidance)
      .hash(earlier)
      .digest();
}

SynthesisCache::SynthesisCache(std::optional<fs::path> dir, Warnings& warnings)
    : dir_(std::move(dir)), warnings_(warnings) {
  if (dir_) folder_ = std::make_unique<CacheFolder>(*dir_, warnings_);
}

ContentHash SynthesisCache::exemplar_hash(const fs::path& path) {
  auto it = exemplars_.find(path);
  if (it == exemplars_.end()) it = exemplars_.emplace(path, exemplar_file_hash(path)).first;
  return it->second;
}

std::optional<Exemplar> SynthesisCache::remembered(const fs::path& path) {
  if (!dir_) return std::nullopt;
  return remembered_exemplar(*dir_, exemplar_hash(path), path);
}

SynthesisKey SynthesisCache::key(const PipelineConfig& config,
                                 const FeatureClassConfig& feature_class, const LineFeature& line,
                                 std::uint64_t feature_seed, const GridSpec& canvas,
                                 const AvoidanceInputs& fixed,
                                 const std::vector<EarlierSynthesis>& earlier,
                                 const std::vector<PieceBinding>& bindings,
                                 const std::vector<Vec2>& junctions, int atlas_gap) {
  SynthesisKey key;
  Hasher g;
  g.points(line.points)
      .boolean(line.closed)
      .real(line.width)
      .u64(std::uint64_t(line.structure))
      .i64(line.layer);
  g.u64(bindings.size());
  for (const PieceBinding& b : bindings) g.boolean(b.line_matches);
  key.geometry = g.digest();

  const SynthesisConfig& s = *method_options<SynthesisConfig>(feature_class, kPatternsMethodName);
  Hasher c;
  c.u64(kSynthesisCacheFormat).text(version_line());
  c.u64(config.seed).real(config.synthesis_resolution).u64(feature_seed);
  c.u64(s.exemplars.size());
  for (const fs::path& path : s.exemplars) c.text(path.string());
  c.u64(std::uint64_t(s.choice)).real(class_piece_length(feature_class)).real(s.scale);
  c.boolean(s.width.has_value()).real(s.width.value_or(0.0));
  c.boolean(s.stitch).boolean(s.empty_pieces).boolean(s.continuous_alpha);
  c.boolean(s.min_coverage.has_value()).real(s.min_coverage.value_or(0.0));
  c.u64(std::uint64_t(s.objective)).real(s.coverage_weight);
  c.u64(s.seed);
  c.i64(s.switch_cost).i64(atlas_gap).u64(s.bind.size());
  for (const ExemplarBinding& b : s.bind) {
    c.u64(b.exemplar).text(b.where).real(b.near_junction).u64(b.tags.size());
    for (const TagSelection& t : b.tags) {
      c.text(t.key).u64(t.values.size());
      for (const std::string& v : t.values) c.text(v);
    }
  }
  key.config = c.digest();

  Hasher e;
  if (s.choice == ExemplarChoice::by_seed) {
    e.hash(exemplar_hash(s.exemplars[feature_seed % s.exemplars.size()]));
  } else {
    for (const fs::path& path : s.exemplars) e.hash(exemplar_hash(path));
  }
  key.exemplar = e.digest();

  // Only what can reach a canvas cell: inputs whose box (lines grown by their width) meets it.
  const PieceBox box = world_box(Window::whole(canvas), canvas);
  Hasher a;
  a.text("polygons");
  hash_polygons_meeting(a, fixed.polygons, box);
  a.text("lines");
  for (std::size_t i = 0; i < fixed.lines.size(); ++i) {
    if (!meets(grown(points_box(fixed.lines[i]), fixed.line_widths[i]), box)) continue;
    a.points(fixed.lines[i]).real(fixed.line_widths[i]);
  }
  a.text("junctions");
  hash_polygons_meeting(a, fixed.junction_discs, box);
  a.text("mix junctions").points(junctions);
  key.avoidance = a.digest();

  // The same overlap test as synthesize_feature uses to burn an earlier feature's coverage.
  Hasher r;
  for (const EarlierSynthesis& before : earlier) {
    if (canvases_overlap(before.canvas, canvas)) r.hash(before.key);
  }
  key.earlier = r.digest();
  return key;
}

fs::path SynthesisCache::entry_path(const ContentHash& key) const {
  return *dir_ / "synthesis" / (key.hex() + ".twc");
}

fs::path SynthesisCache::last_path(const std::string& name) const {
  return *dir_ / "synthesis" / "last" / (Hasher().text(name).digest().hex() + ".twc");
}

fs::path SynthesisCache::input_path(const SynthesisKey& key, const ContentHash& input) const {
  const ContentHash index = Hasher()
                                .text("terraweave.synthesis.by-input")
                                .hash(key.geometry)
                                .hash(key.config)
                                .hash(key.exemplar)
                                .hash(input)
                                .digest();
  return *dir_ / "synthesis" / "inputs" / (index.hex() + ".twc");
}

void SynthesisCache::warn_corrupt(const std::string& subject, std::int64_t fid,
                                  const fs::path& path, const std::string& problem,
                                  CacheStatus& status) {
  warnings_.add("cache_corrupt", subject, fid,
                fmt::format("cache entry {} is corrupt ({}): rebuilt", path.string(), problem));
  status.why = "corrupt entry";
}

std::optional<CachedSynthesis> SynthesisCache::read_entry(const fs::path& path,
                                                          const ContentHash& combined,
                                                          const std::optional<ContentHash>& input,
                                                          const std::string& subject,
                                                          std::int64_t fid, CacheStatus& status) {
  CacheRead read = read_cache_entry(path);
  if (read.state == CacheRead::State::ok) {
    try {
      CachedSynthesis cached;
      const json meta = json::parse(read.sections.at("meta"));
      if (meta.at("key").get<std::string>() != combined.hex()) fail("key mismatch");
      if (input && meta.at("input").get<std::string>() != input->hex()) fail("input mismatch");
      cached.synthesis =
          placements_from_json(read.sections.at("placements"), path.string(), nullptr);
      cached.synthesis.backend = meta.at("backend").get<std::string>();
      cached.exemplar_slot = meta.at("exemplar_slot").get<std::size_t>();
      if (meta.contains("start")) {
        Curve start{{}, true};
        for (const auto& p : meta.at("start")) start.points.push_back({p.at(0), p.at(1)});
        cached.start = std::move(start);
      }
      const GridSpec canvas{meta.at("canvas").at(0), meta.at("canvas").at(1), 0, 0, 1, 1};
      cached.opaque = decode_opaque(read.sections.at("opaque"), canvas);
      // Every value the report had when the entry was built (report.json is the same for a
      // cached and a clean run, timings aside).
      const std::string& report = read.sections.at("report");
      decode(json::from_cbor(report.begin(), report.end()), cached.report, path.string());
      FeatureSynthesisReport& r = cached.report;
      r.avoidance_seconds = r.synthesis_seconds = r.render_seconds = 0.0;
      r.placements.clear();
      if (r.canvas_width != canvas.width || r.canvas_height != canvas.height)
        fail("report canvas {}x{}", r.canvas_width, r.canvas_height);
      touch_cache_entry(path);
      return cached;
    } catch (const std::exception& e) {  // a valid checksum over bytes we cannot use
      read.state = CacheRead::State::corrupt;
      read.problem = fmt::format("unreadable content ({})", single_line(e.what()));
    }
  }
  if (read.state == CacheRead::State::corrupt)
    warn_corrupt(subject, fid, path, read.problem, status);
  return std::nullopt;
}

std::optional<CachedSynthesis> SynthesisCache::find(const std::string& subject, std::int64_t fid,
                                                    const std::string& name,
                                                    const SynthesisKey& key, CacheStatus& status) {
  const ContentHash combined = key.combined();
  status = {false, "no cache", combined.hex()};
  if (!dir_) return std::nullopt;
  status.why = "new";
  std::optional<CachedSynthesis> cached =
      read_entry(entry_path(combined), combined, std::nullopt, subject, fid, status);
  if (cached) {
    status.reused = true;
    status.why = "unchanged";
    return cached;
  }
  if (status.why == "corrupt entry") return std::nullopt;
  const CacheRead last = read_cache_entry(last_path(name));
  if (last.state == CacheRead::State::ok) {
    try {
      status.why = why_changed(key, json::parse(last.sections.at("parts")));
    } catch (const std::exception&) {
      // A record we cannot read only loses the reason.
    }
  }
  return std::nullopt;
}

bool SynthesisCache::finer_check_may_reuse(const CacheStatus& status) {
  return std::find(std::begin(kFinerCheckWhys), std::end(kFinerCheckWhys), status.why) !=
         std::end(kFinerCheckWhys);
}

std::optional<CachedSynthesis> SynthesisCache::find_by_input(const std::string& subject,
                                                             std::int64_t fid,
                                                             const SynthesisKey& key,
                                                             const ContentHash& input,
                                                             CacheStatus& status) {
  if (!dir_) return std::nullopt;
  const fs::path index = input_path(key, input);
  CacheRead read = read_cache_entry(index);
  if (read.state == CacheRead::State::absent) return std::nullopt;
  std::optional<ContentHash> entry;
  if (read.state == CacheRead::State::ok) {
    try {
      entry = ContentHash::from_hex(read.sections.at("entry"));
    } catch (const std::exception& e) {
      read.problem = fmt::format("unreadable content ({})", single_line(e.what()));
    }
  }
  if (!entry) {
    warn_corrupt(subject, fid, index, read.problem, status);
    return std::nullopt;
  }
  const std::string why = status.why;
  std::optional<CachedSynthesis> cached =
      read_entry(entry_path(*entry), *entry, input, subject, fid, status);
  if (!cached) return std::nullopt;  // pruned (status as it was) or corrupt
  status.reused = true;
  status.why = why + ", mask the same";
  return cached;
}

void SynthesisCache::store(const std::string& name, const SynthesisKey& key,
                           const ContentHash& input, const Synthesis& synthesis,
                           std::size_t exemplar_slot, const Curve* start,
                           const SparseRaster<std::uint8_t>& opaque,
                           const FeatureSynthesisReport& report) {
  if (!dir_) return;
  const ContentHash combined = key.combined();
  json meta = {{"key", combined.hex()},
               {"input", input.hex()},
               {"feature", name},
               {"backend", synthesis.backend},
               {"exemplar_slot", exemplar_slot},
               {"canvas", {opaque.width(), opaque.height()}}};
  FeatureSynthesisReport kept = report;  // without what belongs to one run
  kept.avoidance_seconds = kept.synthesis_seconds = kept.render_seconds = 0.0;
  kept.placements.clear();
  const std::vector<std::uint8_t> report_cbor = json::to_cbor(encode(kept));
  if (start) {
    json points = json::array();
    for (const Vec2 p : start->points) points.push_back({p.x, p.y});
    meta["start"] = std::move(points);
  }
  folder_->write(entry_path(combined),
                 {{"meta", meta.dump()},
                  {"placements", placements_to_json(synthesis, report.exemplar)},
                  {"opaque", encode_opaque(opaque)},
                  {"report", std::string(report_cbor.begin(), report_cbor.end())}});
  folder_->write(input_path(key, input), {{"entry", combined.hex()}});
  folder_->write(last_path(name), {{"name", name}, {"parts", encode_parts(key)}});
}

}  // namespace tw::detail
