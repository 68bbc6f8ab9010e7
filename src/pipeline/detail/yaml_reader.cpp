#include "pipeline/detail/yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/eventhandler.h>

#include "core/error.hpp"
#include "geo/input_guard.hpp"
#include "pipeline/detail/variables.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

// True when `path` is `prefix` or lies under it ("a.b" is under "a", "ab" is not).
bool is_under(std::string_view path, std::string_view prefix) {
  return path.size() >= prefix.size() && path.substr(0, prefix.size()) == prefix &&
         (path.size() == prefix.size() || path[prefix.size()] == '.');
}

std::vector<std::string> split_key_path(const Override& o) {
  std::vector<std::string> parts;
  std::string_view rest = o.key_path;
  while (true) {
    const auto dot = rest.find('.');
    const std::string_view part = rest.substr(0, dot);
    if (part.empty()) fail("--set {}={}: empty key in '{}'", o.key_path, o.value, o.key_path);
    parts.emplace_back(part);
    if (dot == std::string_view::npos) break;
    rest.remove_prefix(dot + 1);
  }
  return parts;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

template <class T>
T convert(const YamlSource& src, const YAML::Node& node, const std::string& key_path,
          const char* expected) {
  if (!node.IsScalar()) src.fail(node, key_path, fmt::format("expected {}", expected));
  T value{};
  if (!YAML::convert<T>::decode(node, value)) {
    src.fail(node, key_path, fmt::format("expected {}, got '{}'", expected, node.Scalar()));
  }
  return value;
}

// yaml-cpp keeps every entry of a mapping with a repeated key and looks up the first: a
// repeated key would be silently ignored, so it is an error, in every mapping of the tree.
void require_unique_keys(const YAML::Node& node, const std::string& file_label) {
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) require_unique_keys(item, file_label);
    return;
  }
  if (!node.IsMap()) return;
  std::vector<std::pair<std::string, int>> seen;  // key, line (1-based)
  for (const auto& entry : node) {
    const YAML::Node& key = entry.first;
    if (key.IsScalar()) {
      const std::string name = key.Scalar();
      const auto first =
          std::find_if(seen.begin(), seen.end(), [&](const auto& s) { return s.first == name; });
      if (first != seen.end()) {
        tw::fail("{}:{}:{}: {}: duplicate key (first at line {})", file_label, key.Mark().line + 1,
                 key.Mark().column + 1, name, first->second);
      }
      seen.emplace_back(name, key.Mark().line + 1);
    }
    require_unique_keys(entry.second, file_label);
  }
}

// Where each document starts, for at most `limit` documents. Counted through the event
// parser instead of YAML::LoadAll, which loops forever on some malformed input (yaml-cpp 0.7:
// empty documents without consuming any text; found by fuzz/pipeline_parser).
std::vector<YAML::Mark> document_starts(std::string_view text, std::size_t limit) {
  struct Starts : YAML::EventHandler {
    std::vector<YAML::Mark> marks;
    void OnDocumentStart(const YAML::Mark& mark) override { marks.push_back(mark); }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
  } starts;
  std::istringstream in{std::string(text)};
  YAML::Parser parser(in);
  while (starts.marks.size() < limit && parser.HandleNextDocument(starts)) {
  }
  return starts.marks;
}

}  // namespace

namespace {

// The name without the items that equal `name` (a YAML list of scalars).
YAML::Node without_item(const YAML::Node& list, const std::string& name) {
  YAML::Node kept(YAML::NodeType::Sequence);
  for (const YAML::Node& item : list)
    if (!(item.IsScalar() && item.Scalar() == name)) kept.push_back(item);
  return kept;
}

// `--set key=null` removes the key (a class, an option back to its default). A removed class
// leaves `precedence` and `synthesis_order` too, so dropping one is one flag.
void remove_key(YAML::Node& map, const std::vector<std::string>& parts, const Override& o) {
  const std::string& key = parts.back();
  if (!map.IsMap() || !map[key]) {
    tw::fail("--set {}={}: there is no '{}' to remove (null removes a key that is set)", o.key_path,
             o.value, o.key_path);
  }
  map.remove(key);
}

void drop_from_orders(YAML::Node& root, const std::vector<std::string>& parts) {
  if (parts.size() != 2 || parts[0] != "features") return;
  for (const char* order : {"precedence", "synthesis_order"}) {
    if (root[order] && root[order].IsSequence()) root[order] = without_item(root[order], parts[1]);
  }
}

}  // namespace

YamlSource::YamlSource(std::string file_label, fs::path base_dir, std::vector<Override> overrides,
                       Variables variables)
    : file_label_(std::move(file_label)),
      base_dir_(std::move(base_dir)),
      overrides_(std::move(overrides)),
      variables_(std::move(variables)) {}

namespace {

// Well-formed UTF-8 (RFC 3629: no overlong form, no surrogate, nothing above U+10FFFF), what
// JSON accepts. Not GDAL's CPLIsUTF8: reading a pipeline must not load GDAL (the program loads
// it on first use, docs/performance.md, and a generated world's render-tile needs none).
bool is_utf8(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned lead = byte(i);
    if (lead < 0x80) {
      ++i;
      continue;
    }
    // The sequence's length and the range of its second byte (which rules out overlong forms,
    // surrogates and code points above U+10FFFF); later bytes are 0x80-0xBF.
    std::size_t length = 0;
    unsigned low = 0x80, high = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF)
      length = 2;
    else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) low = 0xA0;
      if (lead == 0xED) high = 0x9F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) low = 0x90;
      if (lead == 0xF4) high = 0x8F;
    } else
      return false;
    if (i + length > text.size() || byte(i + 1) < low || byte(i + 1) > high) return false;
    for (std::size_t k = 2; k < length; ++k)
      if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return false;
    i += length;
  }
  return true;
}

}  // namespace

// YAML is UTF-8 text, and every value ends up in report.json (JSON, UTF-8 only): a Latin-1
// byte must stop here with its line, not later as nlohmann's "invalid UTF-8 byte" with no file.
// The line is found by checking line by line.
void require_utf8(std::string_view text, const std::string& label) {
  if (is_utf8(text)) return;
  std::size_t line_start = 0;
  for (int line = 1;; ++line) {
    const std::size_t end = std::min(text.find('\n', line_start), text.size());
    if (!is_utf8(text.substr(line_start, end - line_start)))
      tw::fail(
          "{}:{}: not UTF-8 text (a pipeline is UTF-8; convert the file, e.g. iconv -f "
          "LATIN1 -t UTF-8)",
          label, line);
    if (end == text.size()) break;
    line_start = end + 1;
  }
  tw::fail(
      "{}: not UTF-8 text (a pipeline is UTF-8; convert the file, e.g. iconv -f LATIN1 -t "
      "UTF-8)",
      label);
}

YAML::Node YamlSource::load(std::string_view text) const {
  require_utf8(text, file_label_);
  for (const Override& o : overrides_) require_utf8(o.key_path + "=" + o.value, "--set");
  YAML::Node root;
  std::vector<YAML::Mark> documents;
  try {
    root = YAML::Load(std::string(text));
    documents = document_starts(text, 2);
  } catch (const YAML::Exception& e) {
    tw::fail("{}:{}:{}: invalid YAML: {}", file_label_, e.mark.line + 1, e.mark.column + 1, e.msg);
  }
  if (documents.size() > 1) {
    const YAML::Mark mark = documents[1];
    tw::fail(
        "{}:{}: a second YAML document, or text after the first that YAML cannot read: a "
        "pipeline file holds one document (remove any '---')",
        file_label_, mark.is_null() ? std::string("end") : std::to_string(mark.line + 1));
  }
  require_unique_keys(root, file_label_);
  if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  substitute_variables(root, variables_, file_label_);
  for (const Override& o : overrides_) {
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      tw::fail("--set {}={}: invalid value: {}", o.key_path, o.value, e.msg);
    }
    const std::vector<std::string> parts = split_key_path(o);
    YAML::Node current = root;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const bool last = i + 1 == parts.size();
      if (current.IsSequence()) {
        std::size_t index = 0;
        const auto [end, ec] =
            std::from_chars(parts[i].data(), parts[i].data() + parts[i].size(), index);
        if (ec != std::errc() || end != parts[i].data() + parts[i].size() ||
            index >= current.size()) {
          tw::fail("--set {}={}: '{}' is not an index of a list of {} items", o.key_path, o.value,
                   parts[i], current.size());
        }
        if (last) {
          current[index] = value;
        } else {
          current.reset(current[index]);
        }
        continue;
      }
      if (!current.IsMap() && !current.IsNull()) {
        tw::fail("--set {}={}: '{}' is a value, not a mapping", o.key_path, o.value, parts[i - 1]);
      }
      if (last && value.IsNull()) {
        remove_key(current, parts, o);
      } else if (last) {
        current[parts[i]] = value;
      } else {
        YAML::Node child = current[parts[i]];
        if (!child.IsDefined() || child.IsNull()) {
          current[parts[i]] = YAML::Node(YAML::NodeType::Map);
          child.reset(current[parts[i]]);
        }
        current.reset(child);
      }
    }
    if (value.IsNull()) drop_from_orders(root, parts);
  }
  return root;
}

const Override* YamlSource::override_for(const std::string& key_path) const {
  // The last override wins, as when the tree was built.
  for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
    if (is_under(key_path, it->key_path)) return &*it;
  }
  return nullptr;
}

std::string YamlSource::location(const YAML::Node& node, const std::string& key_path) const {
  if (const Override* o = override_for(key_path)) {
    return fmt::format("--set {}={}", o->key_path, o->value);
  }
  // An override may have created the maps above its key: an unknown key there is its fault.
  for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
    if (is_under(it->key_path, key_path))
      return fmt::format("--set {}={}", it->key_path, it->value);
  }
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return file_label_;
  return fmt::format("{}:{}:{}", file_label_, mark.line + 1, mark.column + 1);
}

std::string YamlSource::named_at(const YAML::Node& node, const std::string& key_path) const {
  return fmt::format("{}: {}", location(node, key_path),
                     key_path.empty() ? "(top level)" : key_path);
}

void YamlSource::fail(const YAML::Node& node, const std::string& key_path,
                      const std::string& problem) const {
  tw::fail("{}: {}: {}", location(node, key_path), key_path.empty() ? "(top level)" : key_path,
           problem);
}

fs::path YamlSource::resolve(const std::string& value, const std::string& key_path) const {
  // GDAL's virtual file systems and URLs are names, not paths ("/vsizip//vsicurl/..." must keep
  // its "//"); whether they may be opened is check_input_paths' business.
  if (value.starts_with("/vsi") || !network_part_of(value).empty()) return value;
  const fs::path path(value);
  if (path.is_absolute()) return path.lexically_normal();
  const fs::path base = override_for(key_path) ? fs::current_path() : base_dir_;
  return (base / path).lexically_normal();
}

double read_double(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  const double value = convert<double>(src, node, key_path, "a number");
  if (!std::isfinite(value)) src.fail(node, key_path, "must be a finite number");
  return value;
}

double read_positive(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  const double value = read_double(src, node, key_path);
  if (!(value > 0.0)) src.fail(node, key_path, fmt::format("must be > 0, got {}", value));
  return value;
}

double read_non_negative(const YamlSource& src, const YAML::Node& node,
                         const std::string& key_path) {
  const double value = read_double(src, node, key_path);
  if (value < 0.0) src.fail(node, key_path, fmt::format("must be >= 0, got {}", value));
  return value;
}

int read_int(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  return convert<int>(src, node, key_path, "an integer");
}

std::uint64_t read_uint64(const YamlSource& src, const YAML::Node& node,
                          const std::string& key_path) {
  return convert<std::uint64_t>(src, node, key_path, "a non-negative integer");
}

bool read_bool(const YamlSource& src, const YAML::Node& node, const std::string& key_path) {
  return convert<bool>(src, node, key_path, "true or false");
}

std::string read_string(const YamlSource& src, const YAML::Node& node,
                        const std::string& key_path) {
  if (!node.IsScalar()) src.fail(node, key_path, "expected a string");
  return node.Scalar();
}

MapReader::MapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
                     std::string_view block_name)
    : MapReader(src, node, std::move(key_path), pipeline_block(block_name)) {}

MapReader::MapReader(const YamlSource& src, const YAML::Node& node, std::string key_path,
                     const KeyBlock& block)
    : src_(src), block_(&block), node_(node), key_path_(std::move(key_path)) {
  if (node_.IsNull()) node_ = YAML::Node(YAML::NodeType::Map);
  if (!node_.IsMap()) src_.fail(node, key_path_, "expected a mapping of keys to values");
  std::vector<std::string> allowed;
  for (const KeySpec& k : block.keys) allowed.emplace_back(k.name);
  for (const auto& entry : node_) {
    const YAML::Node& key = entry.first;
    const std::string name = key.IsScalar() ? key.Scalar() : std::string("?");
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    const std::string suggestion = closest_match(name, allowed);
    src_.fail(key, path(name),
              suggestion.empty() ? "unknown key"
                                 : fmt::format("unknown key (did you mean '{}'?)", suggestion));
  }
}

const KeySpec& MapReader::spec(const std::string& key) const {
  const KeySpec* k = block_->find(key);
  if (!k)
    throw std::logic_error(fmt::format("key table: block {} has no key {}", block_->name, key));
  return *k;
}

bool MapReader::has(const std::string& key) const {
  const YAML::Node child = node_[key];
  return child.IsDefined() && !child.IsNull();
}

YAML::Node MapReader::get(const std::string& key) const {
  if (!has(key)) src_.fail(node_, path(key), "missing required key");
  return node_[key];
}

std::string MapReader::path(const std::string& key) const {
  return key_path_.empty() ? key : key_path_ + "." + key;
}

double MapReader::positive_or(const std::string& key, double fallback) const {
  return has(key) ? positive(key) : fallback;
}

double MapReader::non_negative_or(const std::string& key, double fallback) const {
  return has(key) ? read_non_negative(src_, get(key), path(key)) : fallback;
}

int MapReader::int_or(const std::string& key, int fallback) const {
  return has(key) ? read_int(src_, get(key), path(key)) : fallback;
}

bool MapReader::bool_or(const std::string& key, bool fallback) const {
  return has(key) ? read_bool(src_, get(key), path(key)) : fallback;
}

std::string MapReader::string(const std::string& key) const {
  return read_string(src_, get(key), path(key));
}

std::string MapReader::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

fs::path MapReader::file(const std::string& key) const {
  const std::string value = string(key);
  if (value.empty()) src_.fail(get(key), path(key), "empty path");
  return src_.resolve(value, path(key));
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::size_t read_one_of(const MapReader& m, const std::string& key, std::string_view noun,
                        const std::vector<std::string>& options,
                        std::optional<std::size_t> fallback) {
  if (!m.has(key) && fallback) return *fallback;
  const std::string value = m.string(key);
  for (std::size_t i = 0; i < options.size(); ++i)
    if (value == options[i]) return i;
  std::string expected = options.front();
  for (std::size_t i = 1; i < options.size(); ++i)
    expected += (i + 1 == options.size() ? " or " : ", ") + options[i];
  const std::string hint = closest_match(value, options);
  m.source().fail(m.get(key), m.path(key),
                  fmt::format("unknown {} '{}', expected {}{}", noun, value, expected,
                              hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
}

}  // namespace tw::detail
