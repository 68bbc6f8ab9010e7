#pragma once
// JSON files of a run or a plan read with one kind of message: "FILE: not valid JSON at byte N:
// REASON; WHAT_TO_DO" rather than nlohmann's "[json.exception.parse_error.101] ..." text.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string_view>

namespace tw {

// Throws tw::Error naming `path` (which is only used in the message) and the byte.
nlohmann::json parse_json_text(std::string_view text, const std::filesystem::path& path,
                               std::string_view what_to_do);
// Reads the file first (tw::Error naming it when it cannot be read).
nlohmann::json parse_json_file(const std::filesystem::path& path, std::string_view what_to_do);

// nlohmann's exception text without its "[json.exception.type_error.302] " prefix.
std::string json_reason(const std::exception& e);

}  // namespace tw
