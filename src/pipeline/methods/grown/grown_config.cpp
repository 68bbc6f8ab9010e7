#include "pipeline/methods/grown/grown_config.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw::detail {

namespace {

const std::vector<std::string>& grown_kinds() {
  static const std::vector<std::string> kinds{"hedge", "wall", "trail", "ditch"};
  return kinds;
}

// region: [minx, miny, maxx, maxy] | { source, layer, where }
void read_region(const MapReader& m, GrowConfig& g, std::vector<InputFile>& inputs) {
  const YAML::Node node = m.get("region");
  const std::string key = m.path("region");
  if (node.IsSequence()) {
    if (node.size() != 4) m.source().fail(node, key, "expected [minx, miny, maxx, maxy] in metres");
    std::array<double, 4> box{};
    for (std::size_t i = 0; i < 4; ++i)
      box[i] = read_double(m.source(), node[i], key + "." + std::to_string(i));
    if (!(box[0] < box[2] && box[1] < box[3]) ||
        !std::all_of(box.begin(), box.end(), [](double v) { return std::isfinite(v); })) {
      m.source().fail(node, key, "expected [minx, miny, maxx, maxy] with minx < maxx, miny < maxy");
    }
    g.region_box = box;
    return;
  }
  if (!node.IsMap())
    m.source().fail(node, key, "expected [minx, miny, maxx, maxy] or {source, layer, where}");
  const MapReader r(m.source(), node, key, "grow_region");
  g.region_source = r.file("source");
  inputs.push_back({g.region_source, InputFile::Kind::vector,
                    r.source().named_at(r.get("source"), r.path("source"))});
  g.region_layer = r.string_or("layer", "");
  g.region_where = r.string_or("where", "");
}

// An integer within the key table's range of `key`.
int int_in(const MapReader& m, const std::string& key, int fallback) {
  const ValueForm& range = numeric_form(m.spec(key));
  const int lo = int(range.minimum);
  const int hi = int(range.maximum);
  const int value = m.int_or(key, fallback);
  if (value < lo || value > hi)
    m.source().fail(m.get(key), m.path(key),
                    fmt::format("must be in [{}, {}], got {}", lo, hi, value));
  return value;
}

}  // namespace

bool is_grown_kind(const std::string& kind) {
  return std::find(grown_kinds().begin(), grown_kinds().end(), kind) != grown_kinds().end();
}

FeatureKind terrain_kind_of(const std::string& kind) {
  if (kind == "ditch") return FeatureKind::river;
  if (kind == "trail") return FeatureKind::road;
  return FeatureKind::ridge;  // hedge, wall
}

void apply_grown_defaults(const std::string& kind, FeatureClassConfig& f) {
  // Field-scale earthworks: a hedge bank and a dry-stone wall are a metre or so proud of the
  // ground, a ditch a metre deep, a trail a narrow graded path that may climb steeply.
  if (kind == "hedge") {
    f.width = 2.0;
    f.ridge = {1.5, 2.0, 1.5};
  } else if (kind == "wall") {
    f.width = 1.0;
    f.ridge = {1.2, 1.5, 3.0};
  } else if (kind == "trail") {
    f.width = 2.0;
    f.road.max_grade = 0.2;
    f.road.shoulder_width = 0.5;
    f.road.falloff = 3.0;
    f.road.smoothing = 10.0;
  } else if (kind == "ditch") {
    f.width = 1.0;
    f.river.depth = 1.0;
    f.river.bank_width = 0.5;
    f.river.falloff = 2.0;
    f.river.max_carve = 2.0;
  }
}

GrowConfig read_grow(const MapReader& m, const std::string& kind, std::uint64_t default_seed,
                     std::vector<InputFile>& inputs) {
  GrowConfig g;
  g.kind = kind;
  g.element = m.file("element");
  inputs.push_back({g.element, InputFile::Kind::method,
                    m.source().named_at(m.get("element"), m.path("element")), kElementSetRole});
  if (m.has("region")) read_region(m, g, inputs);
  GrowSettings& s = g.settings;
  if (m.has("resolution")) s.resolution = m.positive("resolution");
  s.seed = m.has("seed") ? read_uint64(m.source(), m.get("seed"), m.path("seed")) : default_seed;
  if (m.has("alignment")) {
    const std::string value = m.string("alignment");
    if (value != "growth" && value != "contour") {
      const std::string hint = closest_match(value, {"growth", "contour"});
      m.source().fail(m.get("alignment"), m.path("alignment"),
                      fmt::format("unknown alignment '{}', expected growth or contour{}", value,
                                  hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
    s.contour = value == "contour";
  }
  s.first_fit = m.bool_or("first_fit", s.first_fit);
  s.trials = int_in(m, "trials", s.trials);
  s.max_ornaments = int_in(m, "max_ornaments", s.max_ornaments);
  s.max_elements = int_in(m, "max_elements", s.max_elements);
  if (m.has("coverage_radius")) s.coverage_radius = m.positive("coverage_radius");
  if (m.has("clearance")) s.clearance = m.non_negative_or("clearance", 0.0);
  return g;
}

void read_grown_lines(ClassReading& r) {
  const MapReader& m = r.m;
  if (is_grown_kind(r.kind_name) && !m.has("grow") && !r.lines_made) {
    m.source().fail(m.get("kind"), m.path("kind"),
                    fmt::format("a {} class grows its lines: give a grow: block with at least "
                                "an element set (grow: {{ element: ... }})",
                                r.kind_name));
  }
  if (!m.has("grow")) return;
  // Without tags, `kind` is required, so the kind stays "road" only in a class that fails.
  GrowConfig& grow = method_options<GrowConfig>(r.f, kGrownMethodName);
  grow = read_grow(MapReader(m.source(), m.get("grow"), m.path("grow"), "grow"),
                   r.kind_name.empty() ? "road" : r.kind_name, r.seed, r.inputs);
  if (m.has("tags") || m.has("width_attribute")) {
    const std::string key = m.has("tags") ? "tags" : "width_attribute";
    m.source().fail(m.get(key), m.path(key),
                    "a grown class has no features to read tags or widths from");
  }
  r.lines_made = true;
  // Its source holds the region's polygons, needed unless grow.region gives the region.
  r.reads_source = !grow.region_box && grow.region_source.empty();
  r.lines_without_attributes =
      "a grown class's lines have no attributes for where or tags to select (its source is the "
      "region's polygons)";
}

MethodReader grown_reader() {
  MethodReader reader;
  reader.kinds = grown_kinds();
  reader.terrain_kind = terrain_kind_of;
  reader.kind_defaults = apply_grown_defaults;
  reader.read_lines = read_grown_lines;
  return reader;
}

}  // namespace tw::detail
