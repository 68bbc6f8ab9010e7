#include "pipeline/detail/tag_config.hpp"

namespace tw::detail {

std::vector<TagSelection> read_tags(const MapReader& m) {
  const YAML::Node node = m.get("tags");
  const std::string key = m.path("tags");
  if (!node.IsMap() || node.size() == 0) {
    m.source().fail(node, key, "expected a mapping of tag keys to lists of values");
  }
  std::vector<TagSelection> tags;
  for (const auto& entry : node) {
    TagSelection& tag = tags.emplace_back();
    tag.key = read_string(m.source(), entry.first, key);
    const std::string entry_key = key + "." + tag.key;
    if (tag.key.empty()) m.source().fail(entry.first, key, "empty tag key");
    if (entry.second.IsSequence()) {
      if (entry.second.size() == 0) m.source().fail(entry.second, entry_key, "empty list");
      for (std::size_t i = 0; i < entry.second.size(); ++i) {
        tag.values.push_back(
            read_string(m.source(), entry.second[i], entry_key + "." + std::to_string(i)));
      }
    } else {
      tag.values.push_back(read_string(m.source(), entry.second, entry_key));
    }
  }
  return tags;
}

}  // namespace tw::detail
