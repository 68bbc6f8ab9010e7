#include "pipeline/detail/variables.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "pipeline/detail/yaml_file.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw::detail {
namespace {

bool is_variable_name(const std::string& name) {
  if (name.empty() || std::isdigit((unsigned char)name[0])) return false;
  for (const char c : name)
    if (!std::isalnum((unsigned char)c) && c != '_') return false;
  return true;
}

std::string defined_names(const Variables& variables) {
  if (variables.values.empty()) return "it defines none";
  std::string names;
  for (const auto& [name, value] : variables.values) names += (names.empty() ? "" : ", ") + name;
  return "it defines " + names;
}

struct Substitution {
  const Variables& variables;
  const std::string& file_label;

  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& key_path,
                            const std::string& problem) const {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null()) fail("{}: {}: {}", file_label, key_path, problem);
    fail("{}:{}:{}: {}: {}", file_label, mark.line + 1, mark.column + 1, key_path, problem);
  }

  std::string expand(const YAML::Node& node, const std::string& key_path) const {
    const std::string& text = node.Scalar();
    std::string out;
    std::size_t at = 0;
    while (true) {
      const std::size_t open = text.find("${", at);
      if (open == std::string::npos) break;
      const std::size_t close = text.find('}', open + 2);
      if (close == std::string::npos) fail_at(node, key_path, "'${' without its closing '}'");
      const std::string name = text.substr(open + 2, close - open - 2);
      if (!is_variable_name(name)) {
        fail_at(node, key_path,
                fmt::format("${{{}}}: a variable name is letters, digits and '_'", name));
      }
      if (variables.file.empty()) {
        fail_at(node, key_path,
                fmt::format("${{{}}}: no variables file given (--vars FILE)", name));
      }
      const auto found = variables.values.find(name);
      if (found == variables.values.end()) {
        fail_at(node, key_path,
                fmt::format("${{{}}}: not defined in the variables file {} ({})", name,
                            variables.file, defined_names(variables)));
      }
      out += text.substr(at, open - at) + found->second;
      at = close + 1;
    }
    return out + text.substr(at);
  }

  void walk(YAML::Node node, const std::string& key_path) const {
    if (node.IsScalar()) {
      if (node.Scalar().find("${") != std::string::npos) node = expand(node, key_path);
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i)
        walk(node[i], key_path + (key_path.empty() ? "" : ".") + std::to_string(i));
    } else if (node.IsMap()) {
      for (auto entry : node) {
        const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
        walk(entry.second, key_path.empty() ? key : key_path + "." + key);
      }
    }
  }
};

}  // namespace

void substitute_variables(YAML::Node root, const Variables& variables,
                          const std::string& file_label) {
  Substitution{variables, file_label}.walk(root, "");
}

}  // namespace tw::detail

namespace tw {

Variables load_variables(const std::filesystem::path& file) {
  // Bounded before anything is read: `--vars /dev/zero` was a bad_alloc after 28 s.
  const std::string text = detail::read_small_yaml_file(file, "variables");
  detail::require_utf8(text, file.string());
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail("{}:{}:{}: invalid YAML: {}", file.string(), e.mark.line + 1, e.mark.column + 1, e.msg);
  }
  Variables variables;
  variables.file = file.string();
  if (!root.IsDefined() || root.IsNull()) return variables;
  if (!root.IsMap()) fail("{}: expected a mapping of name: value", file.string());
  for (const auto& entry : root) {
    const YAML::Mark mark = entry.first.Mark();
    const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "";
    if (!detail::is_variable_name(name)) {
      fail("{}:{}:{}: '{}': a variable name is letters, digits and '_'", file.string(),
           mark.line + 1, mark.column + 1, name);
    }
    if (!entry.second.IsScalar()) {
      fail("{}:{}:{}: {}: expected a single value (a number or a string)", file.string(),
           mark.line + 1, mark.column + 1, name);
    }
    if (!variables.values.emplace(name, entry.second.Scalar()).second) {
      fail("{}:{}:{}: {}: defined twice", file.string(), mark.line + 1, mark.column + 1, name);
    }
  }
  return variables;
}

}  // namespace tw
