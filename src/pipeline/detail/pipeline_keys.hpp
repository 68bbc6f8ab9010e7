#pragma once
// The one table of a pipeline file's keys: every mapping (a "block") with the keys it allows,
// each key's type, range, allowed values, default and meaning. The reader's MapReaders take
// their allowed keys (and some ranges) from it, and `terraweave schema` writes the JSON Schema
// of docs/pipeline.schema.json from it (pipeline/schema.hpp), so the two cannot disagree. Each
// synthesis method describes its own keys next to its glue (detail/method_keys.hpp); the table
// holds them in their places.
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace tw::detail {

enum class ValueType {
  null_value,       // nothing (export: { unity: })
  number,           // finite, within [minimum, maximum] (exclusive bounds when so marked)
  integer,          // within [minimum, maximum]
  boolean,          // true or false
  string,           // any text
  path,             // a file or folder, relative to the pipeline file's folder; not empty
  choice,           // one of `values`
  choice_list,      // a list of `values`, each at most once
  string_list,      // a list of names
  path_list,        // a list of paths, at least one
  number_list,      // exactly `count` numbers
  block,            // a mapping of the keys of block `block`
  block_list,       // a list of such mappings
  map_string,       // a mapping of names to non-empty strings
  map_number,       // a mapping of names to numbers within [minimum, maximum]
  tags,             // OSM-style tags: a mapping of keys to a value or a non-empty list of values
  channels,         // exemplar channel -> height | splat.<material>
  feature_classes,  // `features`: class name -> line class, or area class with kind: area
};

// One accepted form of a value; a key may accept several (KeySpec::forms).
struct ValueForm {
  ValueType type = ValueType::string;
  double minimum = -std::numeric_limits<double>::infinity();
  double maximum = std::numeric_limits<double>::infinity();
  bool exclusive_minimum = false;  // "> minimum" instead of ">="
  bool exclusive_maximum = false;
  std::vector<std::string_view> values{};  // choice, choice_list
  std::string_view block{};                // block, block_list
  int count = 0;                           // number_list: items; block_list: at least
};

// A default as the schema shows it (the reader's own default structs fill it where they can).
struct KeyDefault {
  enum class Kind { none, number, boolean, text } kind = Kind::none;
  double number = 0.0;
  bool boolean = false;
  std::string_view text{};
};

struct KeySpec {
  std::string_view name{};
  std::vector<ValueForm> forms{};  // one or more accepted forms
  std::string_view description{};
  KeyDefault fallback{};
  bool required = false;
};

struct KeyBlock {
  std::string_view name{};  // e.g. "root", "output", "road_profile"
  std::string_view description{};
  std::vector<KeySpec> keys{};

  const KeySpec* find(std::string_view key) const;
};

// The key's first number or integer form: the range the reader checks (a programming error
// when the key has none: throws std::logic_error).
const ValueForm& numeric_form(const KeySpec& key);

// Every block of the table; "root" is the file's top level.
const std::vector<KeyBlock>& pipeline_blocks();
// The block named `name` (a programming error when there is none: throws std::logic_error).
const KeyBlock& pipeline_block(std::string_view name);

}  // namespace tw::detail
