#include "pipeline/detail/resolved_config.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace tw::detail {
namespace {

nlohmann::json scalar_to_json(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted in the file: a string whatever it reads as
  const char* begin = text.data();
  const char* end = begin + text.size();
  std::int64_t integer = 0;
  if (auto [at, ec] = std::from_chars(begin, end, integer); ec == std::errc() && at == end)
    return integer;
  double number = 0.0;
  if (auto [at, ec] = std::from_chars(begin, end, number);
      ec == std::errc() && at == end && std::isfinite(number))
    return number;
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  if (text == "null" || text == "~" || text.empty()) return nullptr;
  return text;
}

}  // namespace

nlohmann::json yaml_to_json(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return nullptr;
  if (node.IsScalar()) return scalar_to_json(node);
  if (node.IsSequence()) {
    nlohmann::json list = nlohmann::json::array();
    for (const YAML::Node& item : node) list.push_back(yaml_to_json(item));
    return list;
  }
  nlohmann::json map = nlohmann::json::object();
  for (const auto& entry : node)
    map[entry.first.IsScalar() ? entry.first.Scalar() : "?"] = yaml_to_json(entry.second);
  return map;
}

}  // namespace tw::detail
