#include "pipeline/methods/network/network_config.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "pipeline/detail/config_values.hpp"

namespace tw::detail {

namespace {

// "path[:layer]" resolved against the pipeline file's folder; an OGR file is an input (checked
// before the run, listed in the manifest), an SVG is read by the network module only.
std::string source_value(const MapReader& m, const std::string& key,
                         std::vector<InputFile>& inputs) {
  const std::string resolved = m.file(key).string();
  const std::string path = split_source(resolved).first;
  if (!path.ends_with(".svg") && !path.ends_with(".SVG"))
    inputs.push_back({path, InputFile::Kind::vector, m.source().named_at(m.get(key), m.path(key))});
  return resolved;
}

}  // namespace

NetworkClassConfig read_network(const MapReader& m, std::uint64_t default_seed,
                                std::vector<InputFile>& inputs) {
  NetworkClassConfig n;
  n.exemplar = source_value(m, "exemplar", inputs);
  n.exemplar_where = m.string_or("exemplar_where", "");
  if (m.has("exemplar_region")) n.exemplar_region = source_value(m, "exemplar_region", inputs);
  if (m.has("scale")) n.scale = m.positive("scale");
  const YAML::Node region = m.get("region");  // required: a network fills a bounded region
  const std::string key = m.path("region");
  if (region.IsSequence()) {
    if (region.size() != 4)
      m.source().fail(region, key, "expected [minx, miny, maxx, maxy] in metres");
    std::array<double, 4> box{};
    for (std::size_t i = 0; i < 4; ++i)
      box[i] = read_double(m.source(), region[i], key + "." + std::to_string(i));
    if (!(box[0] < box[2] && box[1] < box[3]) ||
        !std::all_of(box.begin(), box.end(), [](double v) { return std::isfinite(v); }))
      m.source().fail(region, key,
                      "expected [minx, miny, maxx, maxy] with minx < maxx, miny < maxy");
    n.region_box = box;
  } else if (region.IsMap()) {
    const MapReader r(m.source(), region, key, "grow_region");
    n.region_source = r.file("source").string();
    inputs.push_back({n.region_source, InputFile::Kind::vector,
                      r.source().named_at(r.get("source"), r.path("source"))});
    n.region_layer = r.string_or("layer", "");
    n.region_where = r.string_or("where", "");
  } else {
    m.source().fail(region, key, "expected [minx, miny, maxx, maxy] or {source, layer, where}");
  }
  if (m.has("partial")) n.partial = source_value(m, "partial", inputs);
  n.seed = m.has("seed") ? read_uint64(m.source(), m.get("seed"), m.path("seed")) : default_seed;
  if (m.has("lead") && m.has("lead_bearing"))
    m.source().fail(m.get("lead_bearing"), m.path("lead_bearing"),
                    "give `lead` or `lead_bearing`, not both (lead_bearing: DEG is lead: "
                    "{ bearing: DEG })");
  if (m.has("lead")) {
    Lead lead = Lead::long_axis;
    read_lead(m, lead, n.lead_bearing_deg);
    n.lead = lead;
  }
  if (m.has("lead_bearing")) {
    const double bearing = read_double(m.source(), m.get("lead_bearing"), m.path("lead_bearing"));
    if (!(bearing >= 0.0 && bearing < 360.0))
      m.source().fail(m.get("lead_bearing"), m.path("lead_bearing"),
                      fmt::format("must be in [0, 360) compass degrees, got {}", bearing));
    n.lead = Lead::bearing;
    n.lead_bearing_deg = bearing;
  }
  n.clearance = m.non_negative_or("clearance", 0.0);
  n.snap = m.non_negative_or("snap", 0.0);
  n.candidates = m.int_or("candidates", n.candidates);
  if (n.candidates < 1 || n.candidates > 1000)
    m.source().fail(m.get("candidates"), m.path("candidates"),
                    fmt::format("must be in [1, 1000], got {}", n.candidates));
  const std::vector<std::string> methods(kNetworkMethodNames.begin(), kNetworkMethodNames.end());
  n.method = methods[read_one_of(m, "method", "method", methods)];
  if (!network_method_completes(network_method_named(n.method)) && !n.partial.empty())
    m.source().fail(m.get("method"), m.path("method"),
                    fmt::format("{} cannot complete `partial`: completing a drawing is growth "
                                "from its ends (use growth or automatic)",
                                n.method));
  n.avoid = m.bool_or("avoid", true);
  return n;
}

void read_network_lines(ClassReading& r) {
  const MapReader& m = r.m;
  if (!m.has("network")) return;
  // The block itself first: a network: that is not a mapping is named as such.
  const MapReader block(m.source(), m.get("network"), m.path("network"), "network");
  for (const char* key : {"grow", "source", "tags", "width_attribute"})
    if (m.has(key))
      m.source().fail(m.get(key), m.path(key),
                      fmt::format("a network class grows its lines: it takes no {} key", key));
  if (r.kind_name.empty())
    m.source().fail(m.node(), m.key_path(),
                    "a network class needs a kind (road, river, ridge, hedge, wall, trail, ditch)");
  method_options<NetworkClassConfig>(r.f, kNetworkMethodName) =
      read_network(block, r.seed, r.inputs);
  r.lines_made = true;
  r.reads_source = false;
  r.lines_without_attributes =
      "a network class's lines are grown and have no attributes for where or tags to select";
}

MethodReader network_reader() {
  MethodReader reader;
  reader.read_lines = read_network_lines;
  return reader;
}

}  // namespace tw::detail
