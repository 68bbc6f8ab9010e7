#include "pipeline/detail/manifest.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <set>

#include "core/file_hash.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

std::string role_of(const InputFile& input) {
  switch (input.kind) {
    case InputFile::Kind::raster:
      return "heightfield";
    case InputFile::Kind::vector:
      return "vector";
    case InputFile::Kind::method:
      return input.role;
  }
  return "input";
}

FileRecord record(std::string role, const fs::path& path, std::string label) {
  FileRecord r{std::move(role), std::move(label), 0, ""};
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return r;  // a URL: nothing to hash here
  const FileDigest digest = file_digest(path);
  r.bytes = digest.bytes;
  r.xxh3_128 = digest.xxh3_128;
  return r;
}

}  // namespace

std::vector<FileRecord> record_inputs(const std::vector<InputFile>& inputs) {
  std::vector<FileRecord> records;
  std::set<fs::path> seen;
  for (const InputFile& input : inputs) {
    if (!seen.insert(input.path).second) continue;
    records.push_back(record(role_of(input), input.path, input.path.string()));
    for (const CompanionFile& companion : input.companions) {
      std::error_code ec;
      if (fs::exists(companion.path, ec) && seen.insert(companion.path).second)
        records.push_back(record(companion.role, companion.path, companion.path.string()));
    }
  }
  return records;
}

std::vector<FileRecord> record_outputs(const OutputFolder& output,
                                       const std::map<fs::path, FileDigest>& known) {
  std::vector<FileRecord> records;
  for (const auto& [relative, staged] : output.staged_files()) {
    if (const auto digest = known.find(relative); digest != known.end()) {
      records.push_back(
          {relative.string(), relative.string(), digest->second.bytes, digest->second.xxh3_128});
      continue;
    }
    records.push_back(record(relative.string(), staged, relative.string()));
  }
  std::sort(records.begin(), records.end(),
            [](const FileRecord& a, const FileRecord& b) { return a.path < b.path; });
  return records;
}

HeightRange height_range(const Raster<float>& height) {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -lo;
  for (const float v : height.pixels) {
    if (std::isnan(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo > hi) return std::nullopt;
  return std::array<float, 2>{lo, hi};
}

std::string utc_timestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace tw::detail
