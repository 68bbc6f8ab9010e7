#include "pipeline/config.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <optional>

#include <ogr_spatialref.h>

#include "core/error.hpp"
#include "geo/features.hpp"
#include "geo/input_guard.hpp"
#include "geo/osm_tags.hpp"
#include "pipeline/detail/config_values.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/resolved_config.hpp"
#include "pipeline/detail/tag_config.hpp"
#include "pipeline/detail/yaml_file.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw {

namespace fs = std::filesystem;
using detail::input_file;
using detail::MapReader;
using detail::read_backend;
using detail::read_one_of;
using detail::read_width;
using detail::YamlSource;

namespace {

bool is_identifier(const std::string& name) {
  const auto letter = [](char c) { return std::isalpha((unsigned char)c) || c == '_'; };
  const auto other = [&](char c) {
    return letter(c) || std::isdigit((unsigned char)c) || c == '-';
  };
  return !name.empty() && letter(name[0]) && std::all_of(name.begin() + 1, name.end(), other);
}

// `repair` (top level or per class): each key overrides `base`.
LineRepair read_repair(const MapReader& m, LineRepair base) {
  base.merge_distance = m.non_negative_or("merge_distance", base.merge_distance);
  base.min_loop = m.non_negative_or("min_loop", base.min_loop);
  base.spike_angle = m.positive_or("spike_angle", base.spike_angle);
  if (base.spike_angle >= 180.0) {
    m.source().fail(m.get("spike_angle"), m.path("spike_angle"),
                    fmt::format("must be below 180 degrees, got {}", base.spike_angle));
  }
  return base;
}

MapReader repair_reader(const MapReader& parent) {
  return MapReader(parent.source(), parent.get("repair"), parent.path("repair"), "repair");
}

const std::vector<detail::MethodReader>& readers() {
  return detail::builtin_method_readers();
}

// The kind as written: a line kind, or one a method adds (the grown kinds).
std::string read_kind_name(const MapReader& m) {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> all{"road", "river", "ridge"};
    for (const detail::MethodReader& reader : readers())
      all.insert(all.end(), reader.kinds.begin(), reader.kinds.end());
    return all;
  }();
  return kinds[read_one_of(m, "kind", "kind", kinds, std::nullopt)];
}

FeatureKind kind_of(const std::string& name) {
  if (name == "road") return FeatureKind::road;
  if (name == "river") return FeatureKind::river;
  if (name == "ridge") return FeatureKind::ridge;
  for (const detail::MethodReader& reader : readers())
    if (std::find(reader.kinds.begin(), reader.kinds.end(), name) != reader.kinds.end())
      return reader.terrain_kind(name);
  fail("kind '{}': no method adds it", name);  // read_kind_name lets only known kinds through
}

GenerateConfig read_generate(const MapReader& m) {
  GenerateConfig g;
  g.width = m.int_or("width", g.width);
  g.height = m.int_or("height", g.height);
  for (const char* key : {"width", "height"}) {
    const int cells = key[0] == 'w' ? g.width : g.height;
    const detail::ValueForm& range = detail::numeric_form(m.spec(key));
    if (cells < range.minimum || cells > range.maximum) {
      m.source().fail(
          m.get(key), m.path(key),
          fmt::format("must be in [{:g}, {:g}], got {}", range.minimum, range.maximum, cells));
    }
  }
  g.pixel_size = m.positive_or("pixel_size", g.pixel_size);
  g.relief = m.non_negative_or("relief", g.relief);
  if (g.relief > kMaxGeneratedRelief) {
    m.source().fail(m.get("relief"), m.path("relief"),
                    fmt::format("must be at most {:g} m, got {:g}", kMaxGeneratedRelief, g.relief));
  }
  g.crs = m.string_or("crs", g.crs);
  if (m.has("origin")) {
    const YAML::Node origin = m.get("origin");
    if (!origin.IsSequence() || origin.size() != 2) {
      m.source().fail(origin, m.path("origin"), "expected [x, y] in metres");
    }
    g.origin_x = detail::read_double(m.source(), origin[0], m.path("origin.0"));
    g.origin_y = detail::read_double(m.source(), origin[1], m.path("origin.1"));
  }
  return g;
}

// The `profile` keys are those of the feature's kind (terrain/features.hpp).
// A length in metres >= 0 and at most the key table's maximum (heights and depths:
// kMaxAbsHeight; widths: kMaxFeatureWidth), so the terrain's heights stay finite floats.
double metres_or(const MapReader& m, const std::string& key, double fallback) {
  const double limit = detail::numeric_form(m.spec(key)).maximum;
  const double value = m.non_negative_or(key, fallback);
  if (value > limit) {
    m.source().fail(m.get(key), m.path(key),
                    fmt::format("must be at most {:g} m, got {:g}", limit, value));
  }
  return value;
}

void read_profile(const detail::YamlSource& src, const YAML::Node& node, const std::string& path,
                  FeatureClassConfig& f) {
  switch (f.kind) {
    case FeatureKind::road: {
      const MapReader m(src, node, path, "road_profile");
      f.road.max_grade = m.positive_or("max_grade", f.road.max_grade);
      f.road.shoulder_width = metres_or(m, "shoulder_width", f.road.shoulder_width);
      f.road.falloff = metres_or(m, "falloff", f.road.falloff);
      f.road.smoothing = metres_or(m, "smoothing", f.road.smoothing);
      if (m.has("max_cut")) f.road.max_cut = metres_or(m, "max_cut", 0.0);
      if (m.has("max_fill")) f.road.max_fill = metres_or(m, "max_fill", 0.0);
      break;
    }
    case FeatureKind::river: {
      const MapReader m(src, node, path, "river_profile");
      f.river.depth = metres_or(m, "depth", f.river.depth);
      f.river.bank_width = metres_or(m, "bank_width", f.river.bank_width);
      f.river.falloff = metres_or(m, "falloff", f.river.falloff);
      f.river.min_slope = m.non_negative_or("min_slope", f.river.min_slope);
      if (m.has("max_carve")) f.river.max_carve = m.non_negative_or("max_carve", 0.0);
      break;
    }
    case FeatureKind::ridge: {
      const MapReader m(src, node, path, "ridge_profile");
      f.ridge.height = metres_or(m, "height", f.ridge.height);
      f.ridge.falloff = metres_or(m, "falloff", f.ridge.falloff);
      f.ridge.sharpness = m.positive_or("sharpness", f.ridge.sharpness);
      break;
    }
  }
}

// Without `kind`, the tag keys decide it (highway: road, waterway: river, natural: ridge).
FeatureKind kind_from_tags(const MapReader& m, const std::vector<TagSelection>& tags) {
  std::string kind;
  for (const TagSelection& tag : tags) {
    const std::string_view implied = osm_kind_of_key(tag.key);
    if (implied.empty()) continue;
    if (!kind.empty() && kind != implied) {
      m.source().fail(m.get("tags"), m.path("tags"),
                      fmt::format("the tag keys imply both {} and {}; give kind", kind, implied));
    }
    kind = implied;
  }
  if (kind == "river") return FeatureKind::river;
  if (kind == "ridge") return FeatureKind::ridge;
  if (kind == "road") return FeatureKind::road;
  m.source().fail(m.get("tags"), m.path("tags"),
                  "no tag key implies a kind (highway, waterway or natural); give kind");
}

FeatureClassConfig read_feature_class(const MapReader& m, const std::string& name,
                                      std::uint64_t seed, const LineRepair& repair,
                                      std::vector<InputFile>& inputs) {
  FeatureClassConfig f;
  f.name = name;
  const std::string kind_name = m.has("kind") ? read_kind_name(m) : "";
  detail::ClassReading r{m, kind_name, seed, inputs, f};
  // The methods that make a class's lines read their blocks first (a network's, a grown
  // class's): such a class reads its source only as the method says (a grown class's region).
  for (const detail::MethodReader& reader : readers())
    if (reader.read_lines) reader.read_lines(r);
  if (!r.lines_made || m.has("source") || r.reads_source)
    f.source = input_file(m, "source", InputFile::Kind::vector, inputs);
  f.layer = m.string_or("layer", "");
  f.where = m.string_or("where", "");
  if (m.has("tags")) f.tags = detail::read_tags(m);
  if (!kind_name.empty()) {
    f.kind = kind_of(kind_name);
  } else {
    f.kind = f.tags.empty() ? kind_of(read_kind_name(m)) : kind_from_tags(m, f.tags);
  }
  if (r.lines_made) {
    for (const detail::MethodReader& reader : readers())
      if (reader.kind_defaults) reader.kind_defaults(kind_name, f);
    if (m.has("width")) f.width = read_width(m, "width");
    if (f.width <= 0.0) f.width = read_width(m, "width");  // road, river, ridge + grow: required
  } else {
    f.width_attribute = m.string_or("width_attribute", "");
    if ((f.width_attribute.empty() && f.tags.empty()) || m.has("width")) {
      f.width = read_width(m, "width");
    }
  }
  if (m.has("profile")) read_profile(m.source(), m.get("profile"), m.path("profile"), f);
  if (m.has("conform")) {
    if (r.lines_made) {
      m.source().fail(m.get("conform"), m.path("conform"),
                      "grown lines are drawn on the surface already; conform applies to lines "
                      "read from a source");
    }
    if (f.kind == FeatureKind::road) {
      m.source().fail(m.get("conform"), m.path("conform"),
                      "roads keep their line (bound their earthwork with profile.max_cut and "
                      "profile.max_fill); conform applies to rivers and ridges");
    }
    const MapReader conform(m.source(), m.get("conform"), m.path("conform"), "conform");
    f.conform_corridor = conform.positive("corridor");
  }
  f.repair = m.has("repair") ? read_repair(repair_reader(m), repair) : repair;
  for (const detail::MethodReader& reader : readers())
    if (reader.read_class) reader.read_class(r);
  return f;
}

ExistingConfig read_existing(const MapReader& m, std::vector<InputFile>& inputs) {
  ExistingConfig e;
  e.source = input_file(m, "source", InputFile::Kind::vector, inputs);
  e.layer = m.string_or("layer", "");
  e.where = m.string_or("where", "");
  if (m.has("tags")) e.tags = detail::read_tags(m);
  e.width = m.has("width") ? read_width(m, "width") : 0.0;
  return e;
}

// Orders the feature classes by `precedence` (lowest first), which must name each exactly once.
// Area classes are painted after every line class (docs/pipeline.md, "Areas") and take no part
// in the order, so naming one is refused with what to do instead.
void apply_precedence(const MapReader& root, std::vector<FeatureClassConfig>& features,
                      const std::map<std::string, std::string>& own_classes) {
  if (!root.has("precedence")) return;
  const YAML::Node list = root.get("precedence");
  const std::string list_path = root.path("precedence");
  if (!list.IsSequence()) root.source().fail(list, list_path, "expected a list of feature classes");
  std::vector<std::string> names;
  for (const auto& f : features) names.push_back(f.name);
  std::vector<FeatureClassConfig> ordered;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string key = list_path + "." + std::to_string(i);
    const std::string name = detail::read_string(root.source(), list[i], key);
    auto it = std::find_if(features.begin(), features.end(),
                           [&](const FeatureClassConfig& f) { return f.name == name; });
    if (const auto own = own_classes.find(name); own != own_classes.end()) {
      root.source().fail(list[i], key,
                         fmt::format("'{}' is {}; remove it from precedence", name, own->second));
    }
    if (it == features.end()) {
      const bool repeated =
          std::any_of(ordered.begin(), ordered.end(),
                      [&](const FeatureClassConfig& f) { return f.name == name; });
      const std::string hint = detail::closest_match(name, names);
      root.source().fail(
          list[i], key,
          repeated ? fmt::format("'{}' is listed twice", name)
                   : fmt::format("'{}' is not a feature class{}", name,
                                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
    ordered.push_back(std::move(*it));
    features.erase(it);
  }
  if (!features.empty()) {
    root.source().fail(
        list, list_path,
        fmt::format("feature class '{}' is missing from the list", features.front().name));
  }
  features = std::move(ordered);
}

// region: [min_x, min_y, max_x, max_y] in metres, each min below its max.
RegionConfig read_region(const YamlSource& src, const YAML::Node& node) {
  if (!node.IsSequence() || node.size() != 4) {
    src.fail(node, "region", "expected [min_x, min_y, max_x, max_y] in metres");
  }
  std::array<double, 4> v{};
  for (std::size_t i = 0; i < 4; ++i) {
    v[i] = detail::read_double(src, node[i], "region." + std::to_string(i));
  }
  if (v[0] >= v[2]) {
    src.fail(node, "region", fmt::format("min_x {} is not below max_x {}", v[0], v[2]));
  }
  if (v[1] >= v[3]) {
    src.fail(node, "region", fmt::format("min_y {} is not below max_y {}", v[1], v[3]));
  }
  return {v[0], v[1], v[2], v[3]};
}

// output.tiles: { size: N, overlap: K }, 1 <= N <= kMaxTileSize, 0 <= K <= kMaxTileOverlap.
TilesConfig read_tiles(const MapReader& m) {
  TilesConfig t;
  t.size = read_int(m.source(), m.get("size"), m.path("size"));
  if (t.size < 1 || t.size > kMaxTileSize) {
    m.source().fail(m.get("size"), m.path("size"),
                    fmt::format("must be in [1, {}] pixels, got {}", kMaxTileSize, t.size));
  }
  t.overlap = m.int_or("overlap", 0);
  if (t.overlap < 0 || t.overlap > kMaxTileOverlap) {
    m.source().fail(m.get("overlap"), m.path("overlap"),
                    fmt::format("must be in [0, {}] pixels, got {}", kMaxTileOverlap, t.overlap));
  }
  return t;
}

// output.formats: [exr, geotiff], either or both, each once.
void read_formats(const YamlSource& src, const YAML::Node& node, OutputConfig& output) {
  const std::vector<std::string> formats = {"exr", "geotiff"};
  if (!node.IsSequence() || node.size() == 0)
    src.fail(node, "output.formats", "expected a list of exr and/or geotiff");
  output.exr = output.geotiff = false;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string path = "output.formats." + std::to_string(i);
    const std::string name = detail::read_string(src, node[i], path);
    bool* wanted = name == "exr" ? &output.exr : name == "geotiff" ? &output.geotiff : nullptr;
    if (wanted == nullptr) {
      const std::string hint = detail::closest_match(name, formats);
      src.fail(node[i], path,
               fmt::format("unknown format '{}', expected exr or geotiff{}", name,
                           hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
    if (*wanted) src.fail(node[i], path, fmt::format("'{}' given twice", name));
    *wanted = true;
  }
}

// output.exr_half, .exr_compression, .compress, .predictor, .cog, .overviews, .crs.
void read_output_encoding(const MapReader& out, OutputConfig& output) {
  if (out.has("exr_half"))
    output.exr_pixels = out.bool_or("exr_half", false) ? ExrPixels::half : ExrPixels::float32;
  output.exr_compression = ExrCompression(read_one_of(
      out, "exr_compression", "EXR compression",
      {"automatic", "none", "rle", "zips", "zip", "piz", "pxr24", "b44", "dwaa", "dwab"}));
  output.tiff.compression = TiffCompression(
      read_one_of(out, "compress", "compression", {"zstd", "deflate", "lzw", "none"}));
  output.tiff.predictor =
      TiffPredictor(read_one_of(out, "predictor", "predictor", {"none", "horizontal", "float"}));
  output.tiff.cog = out.bool_or("cog", output.tiff.cog);
  output.tiff.overviews = out.bool_or("overviews", output.tiff.overviews);
  if (out.has("crs")) {
    output.crs = out.string("crs");
    OGRSpatialReference srs;
    // `utm` and `local` are frames the heightfield's reader derives from the DEM (docs).
    if (output.crs != "utm" && output.crs != "local" && !import_crs(srs, output.crs))
      out.source().fail(out.get("crs"), out.path("crs"),
                        fmt::format("PROJ does not know the CRS '{}'", output.crs));
  }
}

// export: [unreal, unity] or {unreal: {size: 1009, nodata_height: 0, tile_size: 505,
// layers: true}, godot: {height: r16}, terrain3d: {}}.
std::vector<EngineExportOptions> read_exports(const YamlSource& src, const YAML::Node& node) {
  const std::vector<std::string> engines = {"unreal", "unity", "godot", "terrain3d"};
  std::vector<EngineExportOptions> out;
  const auto add = [&](const std::string& name, const YAML::Node& at, const std::string& path) {
    const auto it = std::find(engines.begin(), engines.end(), name);
    if (it == engines.end()) {
      const std::string hint = detail::closest_match(name, engines);
      src.fail(at, path,
               fmt::format("unknown engine '{}', expected unreal, unity, godot or terrain3d{}",
                           name, hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
    for (const auto& e : out)
      if (to_string(e.engine) == name) src.fail(at, path, fmt::format("'{}' given twice", name));
    EngineExportOptions& e = out.emplace_back();
    e.engine = Engine(it - engines.begin());
    return &e;
  };
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      add(detail::read_string(src, node[i], "export"), node[i], "export." + std::to_string(i));
  } else if (node.IsMap()) {
    for (const auto& entry : node) {
      const std::string name = detail::read_string(src, entry.first, "export");
      const std::string path = "export." + name;
      EngineExportOptions* e = add(name, entry.first, path);
      if (entry.second.IsNull()) continue;
      const MapReader m(src, entry.second, path, "export_options");
      if (m.has("size")) {
        e->size = m.int_or("size", 0);
        if (!engine_takes_size(e->engine, e->size))
          src.fail(
              m.get("size"), m.path("size"),
              fmt::format("{} takes sizes {}, not {}", name, engine_size_text(e->engine), e->size));
      }
      e->layers = m.bool_or("layers", false);
      if (m.has("tile_size")) {
        e->tile_size = m.int_or("tile_size", 0);
        const auto& sizes = engine_heightmap_sizes(e->engine);
        if ((e->engine == Engine::godot || e->engine == Engine::terrain3d) && *e->tile_size != 0)
          src.fail(m.get("tile_size"), m.path("tile_size"),
                   fmt::format("{} takes one heightmap, not tiles", name));
        if (e->layers && *e->tile_size != 0)
          src.fail(m.get("tile_size"), m.path("tile_size"),
                   "layers are written with one heightmap (tile_size: 0)");
        if (*e->tile_size != 0 && !std::binary_search(sizes.begin(), sizes.end(), *e->tile_size))
          src.fail(m.get("tile_size"), m.path("tile_size"),
                   fmt::format("{} takes tile sizes {} ... {}, not {} (0: one heightmap)", name,
                               sizes.front(), sizes.back(), *e->tile_size));
      }
      if (m.has("nodata_height"))
        e->nodata_height =
            detail::read_double(src, m.get("nodata_height"), m.path("nodata_height"));
      if (m.has("height")) {
        if (e->engine != Engine::godot && e->engine != Engine::terrain3d)
          src.fail(m.get("height"), m.path("height"),
                   "only godot and terrain3d take a height format");
        e->godot_height =
            GodotHeightFormat(read_one_of(m, "height", "height format", {"exr", "r16"}));
      }
    }
  } else {
    src.fail(node, "export", "expected a list of engines or a mapping of engines to options");
  }
  return out;
}

PipelineConfig read_pipeline(const YamlSource& src, const YAML::Node& tree) {
  const MapReader root(src, tree, "", "root");
  PipelineConfig c;
  c.version = read_int(src, root.get("version"), "version");
  if (c.version != 1) src.fail(root.get("version"), "version", "only version 1 is supported");
  if (root.has("seed")) c.seed = detail::read_uint64(src, root.get("seed"), "seed");
  if (root.has("heightfield") && root.has("generate")) {
    src.fail(root.get("generate"), "generate", "give either heightfield or generate, not both");
  }
  if (root.has("heightfield")) {
    c.heightfield = input_file(root, "heightfield", InputFile::Kind::raster, c.inputs);
  }
  if (root.has("generate")) {
    c.generate = read_generate(MapReader(src, root.get("generate"), "generate", "generate"));
  }
  if (root.has("resolution")) c.resolution = root.positive("resolution");
  if (root.has("region")) c.region = read_region(src, root.get("region"));
  c.resampling = read_one_of(root, "resampling", "resampling", {"bilinear", "cubic"}) == 1
                     ? Resampling::cubic
                     : Resampling::bilinear;
  if (root.has("output")) {
    const MapReader out(src, root.get("output"), "output", "output");
    if (out.has("dir")) c.output.dir = out.file("dir");
    if (out.has("formats") && (out.has("exr") || out.has("geotiff")))
      src.fail(out.get("formats"), "output.formats",
               "give either formats or the exr / geotiff booleans, not both");
    if (out.has("formats")) read_formats(src, out.get("formats"), c.output);
    c.output.exr = out.bool_or("exr", c.output.exr);
    c.output.geotiff = out.bool_or("geotiff", c.output.geotiff);
    c.output.preview = out.bool_or("preview", c.output.preview);
    if (out.has("tiles"))
      c.output.tiles = read_tiles(MapReader(src, out.get("tiles"), "output.tiles", "tiles"));
    read_output_encoding(out, c.output);
  } else {
    c.output.dir = src.resolve(c.output.dir.string(), "output.dir");
  }
  if (!c.output.exr && !c.output.geotiff) {
    src.fail(root.get("output"), "output",
             "no layer format left: output.formats needs exr or geotiff (or exr / geotiff true)");
  }
  if (root.has("avoidance")) {
    const MapReader avoidance(src, root.get("avoidance"), "avoidance", "avoidance");
    c.avoidance.max_distance = avoidance.positive_or("max_distance", c.avoidance.max_distance);
  }
  if (root.has("cache")) c.cache_dir = root.file("cache");
  c.backend = read_backend(root, "backend", c.backend);
  c.strict = root.bool_or("strict", c.strict);
  if (root.has("repair")) c.repair = read_repair(repair_reader(root), c.repair);
  if (root.has("export")) c.exports = read_exports(src, root.get("export"));
  const YAML::Node features = root.get("features");
  // The classes a method reads as its own (the areas), and what precedence says of each.
  std::map<std::string, std::string> own_classes;
  if (!features.IsMap())
    src.fail(features, "features", "expected a mapping of class names to classes");
  for (const auto& entry : features) {
    const std::string name = detail::read_string(src, entry.first, "features");
    const std::string path = "features." + name;
    // The name becomes file names (placements/<class>_<fid>.json) and splat channels.
    if (!is_identifier(name)) {
      src.fail(entry.first, path,
               "a class name must start with a letter or '_' and hold only letters, digits, '_' "
               "and '-'");
    }
    const auto own = std::find_if(readers().begin(), readers().end(), [&](const auto& reader) {
      return reader.takes_class && reader.takes_class(entry.second);
    });
    if (own != readers().end()) {
      own->read_own_class(src, entry.second, path, name, c);
      own_classes[name] = own->own_class_note;
      continue;
    }
    c.features.push_back(read_feature_class(MapReader(src, entry.second, path, "line_class"), name,
                                            c.seed, c.repair, c.inputs));
  }
  if (c.features.empty() && own_classes.empty())
    src.fail(root.get("features"), "features", "no feature classes");
  apply_precedence(root, c.features, own_classes);
  detail::RootReading after_classes{root, c};
  for (const detail::MethodReader& reader : readers())
    if (reader.read_root) reader.read_root(after_classes);
  if (root.has("existing")) {
    const YAML::Node list = root.get("existing");
    if (!list.IsSequence()) src.fail(list, "existing", "expected a list of {source, layer}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string key = "existing." + std::to_string(i);
      c.existing.push_back(read_existing(MapReader(src, list[i], key, "existing"), c.inputs));
    }
  }
  return c;
}

}  // namespace

std::string selection_where(const std::vector<TagSelection>& tags, const std::string& where) {
  auto quoted = [](std::string_view text, char quote) {
    std::string out(1, quote);
    for (const char c : text) {
      out += c;
      if (c == quote) out += quote;  // SQL doubles a quote inside quotes
    }
    return out + quote;
  };
  std::string sql;
  for (const TagSelection& tag : tags) {
    sql += sql.empty() ? "" : " AND ";
    sql += quoted(tag.key, '"') + " IN (";
    for (std::size_t i = 0; i < tag.values.size(); ++i) {
      sql += (i ? ", " : "") + quoted(tag.values[i], '\'');
    }
    sql += ")";
  }
  if (where.empty()) return sql;
  return sql.empty() ? where : sql + " AND (" + where + ")";
}

Override parse_override(std::string_view assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    fail("--set {}: expected key.path=value", assignment);
  }
  if (equals + 1 == assignment.size()) {  // YAML would read it as null: the key as if unset
    fail("--set {}: empty value (for an empty string write {}\"\")", assignment, assignment);
  }
  return {std::string(assignment.substr(0, equals)), std::string(assignment.substr(equals + 1))};
}

PipelineConfig parse_pipeline(std::string_view yaml_text, const std::string& file_label,
                              const fs::path& base_dir, const std::vector<Override>& overrides,
                              const Variables& variables) {
  const YamlSource src(file_label, base_dir, overrides, variables);
  const YAML::Node tree = src.load(yaml_text);
  PipelineConfig config = read_pipeline(src, tree);
  config.overrides = overrides;
  config.resolved_json = detail::yaml_to_json(tree).dump();
  return config;
}

void check_input_paths(const PipelineConfig& config, bool allow_network) {
  if (!config.heightfield) check_input_path(config.generate.crs, "generate.crs", allow_network);
  for (const InputFile& input : config.inputs) {
    check_input_path(input.path.string(), input.named_at, allow_network);
  }
}

PipelineConfig load_pipeline(const fs::path& file, const std::vector<Override>& overrides,
                             const Variables& variables) {
  const std::string text = detail::read_small_yaml_file(file, "pipeline");
  const fs::path folder = fs::absolute(file).parent_path();
  PipelineConfig config = parse_pipeline(text, file.string(), folder, overrides, variables);
  config.file = file;
  return config;
}

}  // namespace tw
