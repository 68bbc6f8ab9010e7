#include "synth/placements_io.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>
#include <limits>

#include "core/error.hpp"

namespace tw {
namespace {

using nlohmann::json;
constexpr const char* kFormat = "terraweave.placements";
// Version 2 adds the mix (its layout, each placement's exemplar, ux in its own exemplar); files
// without a mix are still written as version 1, byte for byte as before.
constexpr int kVersion = 1, kMixVersion = 2;

json vec(Vec2 v) {
  return json::array({v.x, v.y});
}

// nlohmann's get<int>() casts a float (or an integer too large for int64) with a plain cast,
// undefined outside int's range: integers are checked before they are converted.
template <class Int>
Int integer(const json& j, const std::string& path, const std::string& key) {
  const bool fits = j.is_number_unsigned()
                        ? j.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<Int>::max())
                        : j.is_number_integer() &&
                              j.get<std::int64_t>() >= std::numeric_limits<Int>::min() &&
                              j.get<std::int64_t>() <= std::numeric_limits<Int>::max();
  if (!fits) fail("placements {}: key \"{}\": expected an integer, got {}", path, key, j.dump());
  return Int(j.get<std::int64_t>());
}

}  // namespace

std::string placements_to_json(const Synthesis& s, const std::string& exemplar_path) {
  json doc;
  doc["format"] = kFormat;
  doc["version"] = s.mix ? kMixVersion : kVersion;
  doc["exemplar"] = exemplar_path;
  doc["column"] = s.column;
  doc["closed"] = s.closed;
  doc["backend"] = s.backend;
  doc["total_cost"] = s.total_cost;
  doc["mean_seam_cost"] = s.mean_seam_cost;
  doc["mean_seam_cost_stitched"] = s.mean_seam_cost_stitched;
  doc["valid_counts"] = s.valid_counts;
  if (s.mix)
    doc["mix"] = {{"x0", s.mix->x0},
                  {"width", s.mix->width},
                  {"height", s.mix->height},
                  {"gap", s.mix->gap},
                  {"pieces_per_exemplar", s.pieces_per_exemplar},
                  {"switches", s.exemplar_switches}};
  json list = json::array();
  for (const Placement& p : s.placements) {
    const int x0 = s.mix && !p.empty ? s.mix->x0[std::size_t(p.exemplar)] : 0;
    list.push_back({{"ux", p.ux - x0},
                    {"uy", p.uy},
                    {"empty", p.empty},
                    {"origin", vec(p.origin)},
                    {"along", vec(p.along)},
                    {"across", vec(p.across)},
                    {"scale", p.scale},
                    {"stitch", p.stitch}});
    if (s.mix) list.back()["exemplar"] = p.exemplar;
  }
  doc["placements"] = std::move(list);
  return doc.dump(1) + '\n';
}

void save_placements(const Synthesis& s, const std::string& exemplar_path,
                     const std::string& path) {
  std::ofstream file(path);
  if (!file) fail("placements {}: cannot open for writing", path);
  file << placements_to_json(s, exemplar_path);
  if (!file) fail("placements {}: write failed", path);
}

Synthesis load_placements(const std::string& path, std::string* exemplar_path) {
  std::ifstream file(path);
  if (!file) fail("placements {}: cannot open", path);
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  return placements_from_json(text, path, exemplar_path);
}

Synthesis placements_from_json(std::string_view text, const std::string& path,
                               std::string* exemplar_path) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    fail("placements {}: not JSON ({})", path, e.what());
  }
  std::string key;
  try {
    key = "format";
    if (doc.at(key).get<std::string>() != kFormat)
      fail("placements {}: key \"format\" is not \"{}\"", path, kFormat);
    key = "version";
    const int version = integer<int>(doc.at(key), path, key);
    if (version != kVersion && version != kMixVersion)
      fail("placements {}: unsupported version {}", path, doc.at(key).dump());
    Synthesis s;
    key = "exemplar";
    const std::string exemplar = doc.at(key).get<std::string>();
    if (exemplar_path) *exemplar_path = exemplar;
    key = "column";
    s.column = integer<int>(doc.at(key), path, key);
    key = "closed";
    s.closed = doc.at(key).get<bool>();
    key = "backend";
    s.backend = doc.at(key).get<std::string>();
    key = "total_cost";
    s.total_cost = integer<std::int64_t>(doc.at(key), path, key);
    key = "mean_seam_cost";
    s.mean_seam_cost = doc.at(key).get<double>();
    key = "mean_seam_cost_stitched";
    s.mean_seam_cost_stitched = doc.at(key).get<double>();
    key = "valid_counts";
    for (const json& count : doc.at(key).get_ref<const json::array_t&>())
      s.valid_counts.push_back(integer<int>(count, path, key));
    if (version == kMixVersion && doc.contains("mix")) {
      const json& mix = doc.at("mix");
      auto ints = [&](const char* name) {
        key = std::string("mix.") + name;
        std::vector<int> out;
        for (const json& v : mix.at(name).get_ref<const json::array_t&>())
          out.push_back(integer<int>(v, path, key));
        return out;
      };
      MixLayout layout;
      layout.x0 = ints("x0");
      layout.width = ints("width");
      layout.height = ints("height");
      s.pieces_per_exemplar = ints("pieces_per_exemplar");
      key = "mix.gap";
      layout.gap = integer<int>(mix.at("gap"), path, key);
      key = "mix.switches";
      s.exemplar_switches = integer<int>(mix.at("switches"), path, key);
      if (layout.x0.empty() || layout.width.size() != layout.x0.size() ||
          layout.height.size() != layout.x0.size())
        fail("placements {}: key \"mix\": x0, width and height need one entry per exemplar", path);
      s.mix = std::move(layout);
    }
    const json& list = doc.at("placements");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& j = list[i];
      key = fmt::format("placements[{}]", i);
      Placement p;
      p.ux = integer<int>(j.at("ux"), path, key + ".ux");
      p.uy = integer<int>(j.at("uy"), path, key + ".uy");
      p.empty = j.at("empty").get<bool>();
      if (s.mix) {
        p.exemplar = integer<int>(j.at("exemplar"), path, key + ".exemplar");
        if (p.exemplar < 0 || p.exemplar >= s.mix->count())
          fail("placements {}: {}.exemplar {} is not one of the mix's {} exemplars", path, key,
               p.exemplar, s.mix->count());
        if (!p.empty) p.ux += s.mix->x0[std::size_t(p.exemplar)];
      }
      auto v = [&](const char* name) {
        const auto a = j.at(name).get<std::vector<double>>();
        if (a.size() != 2) fail("placements {}: {}.{} must have two numbers", path, key, name);
        return Vec2{a[0], a[1]};
      };
      p.origin = v("origin");
      p.along = v("along");
      p.across = v("across");
      p.scale = j.at("scale").get<double>();
      p.stitch = j.at("stitch").get<std::vector<float>>();
      s.placements.push_back(std::move(p));
    }
    return s;
  } catch (const json::exception& e) {
    fail("placements {}: key \"{}\": {}", path, key, e.what());
  }
}

}  // namespace tw
