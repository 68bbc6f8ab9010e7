#include "pipeline/json_file.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/file_io.hpp"

namespace tw {

std::string json_reason(const std::exception& e) {
  std::string text = e.what();
  if (text.starts_with("[json.exception.")) {
    const std::size_t end = text.find("] ");
    if (end != std::string::npos) text.erase(0, end + 2);
  }
  // The position is given separately ("at byte N"); "parse error at line 1, column 5: " repeats it.
  if (text.starts_with("parse error")) {
    const std::size_t colon = text.find(": ");
    if (colon != std::string::npos) text.erase(0, colon + 2);
  }
  return text;
}

nlohmann::json parse_json_text(std::string_view text, const std::filesystem::path& path,
                               std::string_view what_to_do) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    fail("{}: not valid JSON at byte {}: {}; {}", path.string(), e.byte, json_reason(e),
         what_to_do);
  }
}

nlohmann::json parse_json_file(const std::filesystem::path& path, std::string_view what_to_do) {
  return parse_json_text(read_file_bytes(path), path, what_to_do);
}

}  // namespace tw
