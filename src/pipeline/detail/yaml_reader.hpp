#pragma once
// Typed, located reading of a YAML tree: every problem becomes a tw::Error that starts with
// where the value came from ("file:line:col" or "--set key=value") and its key path.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/pipeline_keys.hpp"

namespace tw::detail {

class YamlSource {
 public:
  YamlSource(std::string file_label, std::filesystem::path base_dir,
             std::vector<Override> overrides, Variables variables = {});

  // Loads `text`, substitutes the variables, then applies the overrides to the tree (creating
  // maps on the way).
  YAML::Node load(std::string_view text) const;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key_path,
                         const std::string& problem) const;
  // "file:line:col: key.path" (or "--set key=value: key.path"): the prefix of fail's messages,
  // for problems found later (an input file that cannot be opened).
  std::string named_at(const YAML::Node& node, const std::string& key_path) const;
  // A path value: relative ones resolve against the file's folder, or the current folder
  // for values given with --set.
  std::filesystem::path resolve(const std::string& value, const std::string& key_path) const;

  const std::string& file_label() const { return file_label_; }

 private:
  const Override* override_for(const std::string& key_path) const;
  std::string location(const YAML::Node& node, const std::string& key_path) const;

  std::string file_label_;
  std::filesystem::path base_dir_;
  std::vector<Override> overrides_;
  Variables variables_;
};

// Typed scalars. Each fails with the node's location when the value has the wrong type.
// Fails with "<label>:<line>: not UTF-8 text ..." unless `text` is UTF-8.
void require_utf8(std::string_view text, const std::string& label);

double read_double(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
double read_positive(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
double read_non_negative(const YamlSource& src, const YAML::Node& node,
                         const std::string& key_path);
int read_int(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
std::uint64_t read_uint64(const YamlSource& src, const YAML::Node& node,
                          const std::string& key_path);
bool read_bool(const YamlSource& src, const YAML::Node& node, const std::string& key_path);
std::string read_string(const YamlSource& src, const YAML::Node& node, const std::string& key_path);

// One YAML mapping whose allowed keys are those of `block` in the key table
// (detail/pipeline_keys.hpp, which the JSON Schema is written from); an unknown key fails at
// once, with a "did you mean" suggestion when a known key is close.
class MapReader {
 public:
  MapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
            const KeyBlock& block);
  // The same, naming the block of the key table.
  MapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
            std::string_view block_name);

  bool has(const std::string& key) const;
  YAML::Node get(const std::string& key) const;  // fails when missing
  std::string path(const std::string& key) const;
  const YAML::Node& node() const { return node_; }
  const std::string& key_path() const { return key_path_; }
  const YamlSource& source() const { return src_; }
  // The key's entry in the table (a programming error when the block has no such key).
  const KeySpec& spec(const std::string& key) const;

  double positive(const std::string& key) const { return read_positive(src_, get(key), path(key)); }
  double positive_or(const std::string& key, double fallback) const;
  double non_negative_or(const std::string& key, double fallback) const;
  int int_or(const std::string& key, int fallback) const;
  bool bool_or(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  std::filesystem::path file(const std::string& key) const;

 private:
  const YamlSource& src_;
  const KeyBlock* block_;
  YAML::Node node_;
  std::string key_path_;
};

// The closest of `candidates` to `word` when it is a plausible typo, else "".
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

// The index in `options` of the string at `key`; absent: `fallback`, or the reader's "missing
// key" error without one. Anything else fails as "unknown <noun> 'x', expected a, b or c", with
// a did-you-mean hint when one is close.
std::size_t read_one_of(const MapReader& m, const std::string& key, std::string_view noun,
                        const std::vector<std::string>& options,
                        std::optional<std::size_t> fallback = 0);

}  // namespace tw::detail
