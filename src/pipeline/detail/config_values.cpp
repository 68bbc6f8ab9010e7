#include "pipeline/detail/config_values.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "pipeline/detail/pipeline_keys.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

fs::path input_file(const MapReader& m, const std::string& key, InputFile::Kind kind,
                    std::vector<InputFile>& inputs) {
  const fs::path path = m.file(key);
  inputs.push_back({path, kind, m.source().named_at(m.get(key), m.path(key))});
  return path;
}

double read_width(const MapReader& m, const std::string& key) {
  const double width = m.positive(key);
  const double limit = numeric_form(m.spec(key)).maximum;
  if (width > limit) {
    m.source().fail(m.get(key), m.path(key),
                    fmt::format("must be at most {:g} m, got {:g}", limit, width));
  }
  return width;
}

std::string read_backend(const MapReader& m, const std::string& key, const std::string& fallback) {
  static const std::vector<std::string> backends{"cpu", "opencl", "auto"};
  const auto fallback_index =
      std::size_t(std::find(backends.begin(), backends.end(), fallback) - backends.begin());
  return backends[read_one_of(m, key, "backend", backends,
                              std::min<std::size_t>(fallback_index, 2))];
}

void read_lead(const MapReader& m, Lead& lead, double& bearing_deg) {
  if (!m.has("lead")) return;
  const YAML::Node node = m.get("lead");
  const std::string key = m.path("lead");
  if (node.IsMap()) {
    const MapReader fixed(m.source(), node, key, "lead");
    lead = Lead::bearing;
    bearing_deg = read_double(m.source(), fixed.get("bearing"), fixed.path("bearing"));
    if (!std::isfinite(bearing_deg))
      m.source().fail(fixed.get("bearing"), fixed.path("bearing"), "must be a finite angle");
    return;
  }
  const std::string value = read_string(m.source(), node, key);
  const std::vector<std::string> names = {"long_axis", "nearest_road", "contours"};
  const auto it = std::find(names.begin(), names.end(), value);
  if (it == names.end()) {
    const std::string hint = closest_match(value, names);
    m.source().fail(
        node, key,
        fmt::format("unknown lead '{}', expected long_axis, nearest_road, contours or "
                    "{{ bearing: DEG }}{}",
                    value, hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
  }
  lead = std::array{Lead::long_axis, Lead::nearest_road,
                    Lead::contours}[std::size_t(it - names.begin())];
}

}  // namespace tw::detail
