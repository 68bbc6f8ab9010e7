#include "pipeline/detail/config_values.hpp"

#include <algorithm>

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

}  // namespace tw::detail
