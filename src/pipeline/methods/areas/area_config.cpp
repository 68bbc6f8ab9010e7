#include "pipeline/methods/areas/area_config.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "pipeline/detail/config_values.hpp"
#include "pipeline/detail/tag_config.hpp"

namespace tw::detail {

namespace {

// The entry of `stroke` in a.materials, added when missing.
AreaMaterial& material_of(AreaClassConfig& a, const std::string& stroke) {
  const auto it = std::find_if(a.materials.begin(), a.materials.end(),
                               [&](const AreaMaterial& m) { return m.stroke == stroke; });
  return it != a.materials.end() ? *it : a.materials.emplace_back(AreaMaterial{stroke, "", 0.0});
}

// materials: { stroke: splat_material }, height: { stroke: metres }.
void read_materials(const MapReader& m, AreaClassConfig& a) {
  for (const char* key : {"materials", "height"}) {
    if (!m.has(key)) continue;
    const YAML::Node node = m.get(key);
    if (!node.IsMap() || node.size() == 0)
      m.source().fail(node, m.path(key), "expected a mapping of sketch stroke materials");
    for (const auto& entry : node) {
      const std::string stroke = read_string(m.source(), entry.first, m.path(key));
      const std::string entry_key = m.path(key) + "." + stroke;
      AreaMaterial& material = material_of(a, stroke);
      if (key[0] == 'm') {
        material.splat = read_string(m.source(), entry.second, entry_key);
        if (material.splat.empty()) m.source().fail(entry.second, entry_key, "empty material");
      } else {
        material.height = read_double(m.source(), entry.second, entry_key);
        if (!(std::abs(material.height) <= 100.0))
          m.source().fail(entry.second, entry_key,
                          fmt::format("must be within +-100 m, got {}", material.height));
      }
    }
  }
}

}  // namespace

MapReader area_class_reader(const YamlSource& src, const YAML::Node& node,
                            const std::string& path) {
  return MapReader(src, node, path, "area_class");
}

bool is_area_class(const YAML::Node& node) {
  return node.IsMap() && node["kind"] && node["kind"].IsScalar() && node["kind"].Scalar() == "area";
}

AreaClassConfig read_area_class(const MapReader& m, const std::string& name,
                                std::uint64_t default_seed, std::vector<InputFile>& inputs) {
  AreaClassConfig a;
  a.name = name;
  a.source = input_file(m, "source", InputFile::Kind::vector, inputs);
  a.layer = m.string_or("layer", "");
  // `tags` (OSM-style, ANDed with `where`) read as the SQL they select.
  a.where = selection_where(m.has("tags") ? read_tags(m) : std::vector<TagSelection>{},
                            m.string_or("where", ""));
  a.sketch = input_file(m, "sketch", InputFile::Kind::vector, inputs);
  if (m.has("shapes_from"))
    a.shapes_from = input_file(m, "shapes_from", InputFile::Kind::vector, inputs);
  a.scale = m.positive_or("scale", a.scale);
  read_lead(m, a.lead, a.bearing_deg);
  a.jitter = m.non_negative_or("jitter", a.jitter);
  if (a.jitter > 1.0)
    m.source().fail(
        m.get("jitter"), m.path("jitter"),
        fmt::format("must be in [0, 1] (a fraction of each allowed displacement), got {}",
                    a.jitter));
  a.seed = m.has("seed") ? read_uint64(m.source(), m.get("seed"), m.path("seed")) : default_seed;
  read_materials(m, a);
  return a;
}

namespace {

void read_area_class_into(const YamlSource& src, const YAML::Node& node, const std::string& path,
                          const std::string& name, PipelineConfig& config) {
  AreaClassConfig area =
      read_area_class(area_class_reader(src, node, path), name, config.seed, config.inputs);
  method_options<AreaOptions>(config, kAreasMethodName).classes.push_back(std::move(area));
}

}  // namespace

const std::vector<AreaClassConfig>& area_classes(const PipelineConfig& config) {
  static const std::vector<AreaClassConfig> none;
  const AreaOptions* options = method_options<AreaOptions>(config, kAreasMethodName);
  return options ? options->classes : none;
}

MethodReader area_reader() {
  MethodReader reader;
  reader.takes_class = is_area_class;
  reader.read_own_class = read_area_class_into;
  reader.own_class_note =
      "an area class (kind: area): areas are painted after every line class and are not ordered";
  return reader;
}

}  // namespace tw::detail
