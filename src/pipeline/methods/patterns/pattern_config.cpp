#include "pipeline/methods/patterns/pattern_config.hpp"

#include <algorithm>
#include <cctype>

#include "core/error.hpp"
#include "pipeline/detail/config_values.hpp"
#include "pipeline/detail/tag_config.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

// A colour unit is a 0..255 channel difference: more than this would only overflow costs.
constexpr int kMaxSwitchCost = 1 << 20;

// An exemplar, as the manifest lists it and the patterns' check_input claims it.
void add_exemplar_input(const fs::path& path, std::string named_at,
                        std::vector<InputFile>& inputs) {
  inputs.push_back({path,
                    InputFile::Kind::method,
                    std::move(named_at),
                    kExemplarRole,
                    {{exemplar_height_path(path), kExemplarHeightRole}}});
}

// `bind: [{exemplar: PATH-or-index, where, tags, near_junction}]` (choose: mix). The exemplar is
// an index into the list or one of its paths (resolved as the list's are).
std::vector<ExemplarBinding> read_bindings(const MapReader& m,
                                           const std::vector<fs::path>& exemplars) {
  const YAML::Node list = m.get("bind");
  const std::string list_key = m.path("bind");
  if (!list.IsSequence() || list.size() == 0)
    m.source().fail(list, list_key, "expected a list of {exemplar, where, tags, near_junction}");
  std::vector<ExemplarBinding> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string key = list_key + "." + std::to_string(i);
    const MapReader r(m.source(), list[i], key, "binding");
    ExemplarBinding& b = out.emplace_back();
    b.key = key;
    const YAML::Node e = r.get("exemplar");
    const std::string value = read_string(m.source(), e, r.path("exemplar"));
    const bool is_index = !value.empty() && std::all_of(value.begin(), value.end(), [](char ch) {
      return std::isdigit((unsigned char)ch);
    });
    if (is_index) {
      b.exemplar = std::size_t(read_uint64(m.source(), e, r.path("exemplar")));
      if (b.exemplar >= exemplars.size()) {
        m.source().fail(e, r.path("exemplar"),
                        fmt::format("exemplar {} of a list of {} (indices start at 0)", b.exemplar,
                                    exemplars.size()));
      }
    } else {
      const fs::path path = m.source().resolve(value, r.path("exemplar"));
      const auto it = std::find(exemplars.begin(), exemplars.end(), path);
      if (it == exemplars.end()) {
        std::vector<std::string> names;
        for (const fs::path& p : exemplars) names.push_back(p.filename().string());
        m.source().fail(e, r.path("exemplar"),
                        fmt::format("'{}' is not one of the class's exemplars ({})", value,
                                    fmt::join(names, ", ")));
      }
      b.exemplar = std::size_t(it - exemplars.begin());
    }
    b.where = r.string_or("where", "");
    if (r.has("tags")) b.tags = read_tags(r);
    b.near_junction = r.non_negative_or("near_junction", 0.0);
    if (b.near_junction > kMaxFeatureWidth) {
      m.source().fail(
          r.get("near_junction"), r.path("near_junction"),
          fmt::format("must be at most {:g} m, got {:g}", kMaxFeatureWidth, b.near_junction));
    }
    if (b.where.empty() && b.tags.empty() && b.near_junction <= 0.0) {
      m.source().fail(list[i], key,
                      "a binding needs where, tags or near_junction (else it binds every piece; "
                      "list only that exemplar instead)");
    }
  }
  return out;
}

SynthesisConfig read_synthesis(const MapReader& m, std::uint64_t default_seed,
                               std::vector<InputFile>& inputs) {
  SynthesisConfig s;
  const YAML::Node exemplar = m.get("exemplar");
  if (exemplar.IsSequence()) {
    if (exemplar.size() == 0) m.source().fail(exemplar, m.path("exemplar"), "empty list");
    for (std::size_t i = 0; i < exemplar.size(); ++i) {
      const std::string key = m.path("exemplar") + "." + std::to_string(i);
      const std::string value = read_string(m.source(), exemplar[i], key);
      if (value.empty()) m.source().fail(exemplar[i], key, "empty path");
      s.exemplars.push_back(m.source().resolve(value, key));
      add_exemplar_input(s.exemplars.back(), m.source().named_at(exemplar[i], key), inputs);
    }
  } else {
    s.exemplars.push_back(m.file("exemplar"));
    add_exemplar_input(s.exemplars.back(),
                       m.source().named_at(m.get("exemplar"), m.path("exemplar")), inputs);
  }
  if (m.has("delta")) s.delta = m.positive("delta");
  s.scale = m.positive_or("scale", s.scale);
  s.stitch = m.bool_or("stitch", s.stitch);
  if (m.has("width") && m.get("width").IsScalar() && m.get("width").Scalar() == "feature")
    s.width_of_feature = true;
  else if (m.has("width"))
    s.width = read_width(m, "width");
  s.empty_pieces = m.bool_or("empty_pieces", s.empty_pieces);
  s.seed = m.has("seed") ? read_uint64(m.source(), m.get("seed"), m.path("seed")) : default_seed;
  if (m.has("backend")) s.backend = read_backend(m, "backend", "auto");
  s.height_detail = m.non_negative_or("height_detail", s.height_detail);
  if (m.has("min_coverage")) s.min_coverage = m.non_negative_or("min_coverage", 0.0);
  s.feather = m.non_negative_or("feather", s.feather);
  if (s.min_coverage && *s.min_coverage >= 1.0) {
    m.source().fail(
        m.get("min_coverage"), m.path("min_coverage"),
        fmt::format("must be below 1 (a fraction of each piece), got {}", *s.min_coverage));
  }
  s.objective = read_one_of(m, "objective", "objective", {"pattern", "paper"}) == 1
                    ? Objective::paper
                    : Objective::pattern;
  s.coverage_weight = m.non_negative_or("coverage_weight", s.coverage_weight);
  s.continuous_alpha = read_one_of(m, "alpha", "alpha", {"binary", "continuous"}) == 1;
  static const ExemplarChoice choices[] = {ExemplarChoice::by_seed, ExemplarChoice::best,
                                           ExemplarChoice::mix};
  s.choice = choices[read_one_of(m, "choose", "choice", {"seed", "best", "mix"})];
  for (const char* key : {"switch_cost", "bind"}) {
    if (m.has(key) && s.choice != ExemplarChoice::mix)
      m.source().fail(m.get(key), m.path(key), "only with choose: mix");
  }
  if (m.has("switch_cost")) {
    const int cost = m.int_or("switch_cost", 0);
    if (cost < 0 || cost > kMaxSwitchCost) {
      m.source().fail(m.get("switch_cost"), m.path("switch_cost"),
                      fmt::format("must be in [0, {}] colour units, got {}", kMaxSwitchCost, cost));
    }
    s.switch_cost = cost;
  }
  if (m.has("bind")) s.bind = read_bindings(m, s.exemplars);
  if (m.has("channels")) {
    const YAML::Node channels = m.get("channels");
    const std::string key = m.path("channels");
    if (!channels.IsMap() || channels.size() == 0) {
      m.source().fail(channels, key, "expected a mapping of exemplar channels to outputs");
    }
    for (const auto& entry : channels) {
      std::string channel = read_string(m.source(), entry.first, key);
      const std::string entry_key = key + "." + channel;
      const std::string target = read_string(m.source(), entry.second, entry_key);
      const bool splat = target.rfind("splat.", 0) == 0 && target.size() > 6;
      if (target != "height" && !splat) {
        m.source().fail(
            entry.second, entry_key,
            fmt::format("unknown output '{}', expected height or splat.<material>", target));
      }
      if (channel == "alpha") channel = "A";
      s.channels.push_back({channel, target});
    }
  }
  return s;
}

// `synthesis_order`: each class with synthesis exactly once; default precedence order.
void read_synthesis_order(const MapReader& root, PipelineConfig& c) {
  std::vector<std::string> order;
  std::vector<std::string> with_synthesis;
  for (const auto& f : c.features) {
    if (has_method_options(f, kPatternsMethodName)) with_synthesis.push_back(f.name);
  }
  if (!root.has("synthesis_order")) {
    if (!with_synthesis.empty())
      method_options<SynthesisOrder>(c, kPatternsMethodName).classes = with_synthesis;
    return;
  }
  const YAML::Node list = root.get("synthesis_order");
  const std::string list_path = root.path("synthesis_order");
  if (!list.IsSequence()) root.source().fail(list, list_path, "expected a list of feature classes");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string key = list_path + "." + std::to_string(i);
    const std::string name = read_string(root.source(), list[i], key);
    if (std::find(order.begin(), order.end(), name) != order.end()) {
      root.source().fail(list[i], key, fmt::format("'{}' is listed twice", name));
    }
    if (std::find(with_synthesis.begin(), with_synthesis.end(), name) == with_synthesis.end()) {
      const std::string hint = closest_match(name, with_synthesis);
      root.source().fail(
          list[i], key,
          fmt::format("'{}' is not a feature class with synthesis{}", name,
                      hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
    order.push_back(name);
  }
  for (const std::string& name : with_synthesis) {
    if (std::find(order.begin(), order.end(), name) == order.end()) {
      root.source().fail(
          list, list_path,
          fmt::format("feature class '{}' (with synthesis) is missing from the list", name));
    }
  }
  if (!order.empty()) method_options<SynthesisOrder>(c, kPatternsMethodName).classes = order;
}

}  // namespace

fs::path exemplar_height_path(const fs::path& exemplar) {
  return exemplar.parent_path() / (exemplar.stem().string() + "_height.tif");
}

void read_pattern_class(ClassReading& r) {
  const MapReader& m = r.m;
  if (!m.has("synthesis")) return;
  FeatureClassConfig& f = r.f;
  SynthesisConfig& synthesis = method_options<SynthesisConfig>(f, kPatternsMethodName);
  synthesis =
      read_synthesis(MapReader(m.source(), m.get("synthesis"), m.path("synthesis"), "synthesis"),
                     r.seed, r.inputs);
  // Lines a method made (a network's, a grown class's) have no layer for a where or tags rule to
  // ask (a grown class's source holds its region's polygons, whose FIDs are not the lines').
  for (std::size_t i = 0; r.lines_made && i < synthesis.bind.size(); ++i)
    if (!synthesis.bind[i].where.empty() || !synthesis.bind[i].tags.empty())
      m.source().fail(m.get("synthesis")["bind"][i], synthesis.bind[i].key,
                      fmt::format("{}; bind them by near_junction", r.lines_without_attributes));
}

void read_pattern_root(RootReading& r) {
  if (r.root.has("synthesis_resolution")) {
    r.config.synthesis_resolution = r.root.positive("synthesis_resolution");
  }
  read_synthesis_order(r.root, r.config);
}

MethodReader pattern_reader() {
  MethodReader reader;
  reader.read_class = read_pattern_class;
  reader.read_root = read_pattern_root;
  return reader;
}

}  // namespace tw::detail
