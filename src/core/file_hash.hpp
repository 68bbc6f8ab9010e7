#pragma once
// Content hashes of files for the run manifest (report.json): XXH3-128 from libxxhash, read in
// 1 MiB chunks so that hashing a large input costs no memory.
#include <cstdint>
#include <filesystem>
#include <string>

namespace tw {

struct FileDigest {
  std::uintmax_t bytes = 0;
  std::string xxh3_128;  // 32 lowercase hex digits (XXH128_canonical_t order)
};

// Throws tw::Error naming the file when it cannot be read.
FileDigest file_digest(const std::filesystem::path& path);

}  // namespace tw
