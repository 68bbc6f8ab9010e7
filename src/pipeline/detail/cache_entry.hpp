#pragma once
// One entry of the run cache (docs/cache.md): named sections of bytes in one file, written
// atomically (a temporary in the same folder, then rename) and carrying the XXH3-128 checksum
// of its own payload, so that a truncated, corrupted or foreign file is detected on reading and
// never trusted.
//
// Layout: "TWCACHE1" (8 bytes), payload size (u64 LE), checksum of the payload (16 bytes:
// high, low, u64 LE each), payload = sections, each: name size (u64), name, data size (u64),
// data.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "core/file_hash.hpp"
#include "core/warnings.hpp"

namespace tw::detail {

using CacheSections = std::map<std::string, std::string>;

struct CacheRead {
  enum class State { absent, corrupt, ok };
  State state = State::absent;
  std::string problem;  // for corrupt: what did not match
  CacheSections sections;
};

// Writes `sections` to `path` atomically (creating its folder). Throws tw::Error naming the
// path when the cache cannot be written.
void write_cache_entry(const std::filesystem::path& path, const CacheSections& sections);

// Reads and checks an entry; never throws for a bad file (that is State::corrupt).
CacheRead read_cache_entry(const std::filesystem::path& path);

// A file kept whole in the cache (a tile's output file, docs/cache.md): its own bytes, not a
// container, so that a reuse hard-links it into the output folder instead of copying. It is
// read-only, named by its content hash, and checked against `expected` (size and XXH3-128, read
// through once) before each reuse: an output file edited in place edits the cache file it is
// linked to, and that edit must never reach a later run. State::absent: no such file (pruned).
CacheRead::State check_cache_file(const std::filesystem::path& path, const FileDigest& expected,
                                  std::string& problem);

// Places the checked cache file `path` at `target` (which must not exist): a hard link, or a
// copy where the two lie on different file systems (or links fail). Throws tw::Error naming
// `target` when neither works.
void place_cache_file(const std::filesystem::path& path, const std::filesystem::path& target);

// Marks an entry as used now (its modification time), so that pruning by age keeps what the
// latest runs used. Errors are ignored (a read-only cache still serves).
void touch_cache_entry(const std::filesystem::path& path);

// Creates `dir` with a CACHEDIR.TAG (the Cache Directory Tagging Specification: backup tools
// skip the folder). Throws tw::Error naming it when it cannot be created.
void prepare_cache_dir(const std::filesystem::path& dir);

// The cache folder as one run uses it: prepared (prepare_cache_dir) and share-locked
// (<dir>/.lock, flock) while the run lasts. The first run to find no other holding it sweeps the
// temporaries (.<entry>.tmp*) a killed run left behind: no run is writing them. A folder that
// cannot be prepared, locked or written (no permission, a full disk) is no error: a warning
// `cache_unwritable` says why, once, and the run goes on without storing in the cache (reading
// what is there still serves).
class CacheFolder {
 public:
  CacheFolder(const std::filesystem::path& dir, Warnings& warnings);
  ~CacheFolder();
  CacheFolder(const CacheFolder&) = delete;
  CacheFolder& operator=(const CacheFolder&) = delete;

  // write_cache_entry, unless an earlier write failed; a failure is the warning. Any thread.
  void write(const std::filesystem::path& path, const CacheSections& sections);
  // Keeps `file` (a finished output, hashed as `digest`) as the cache file `path` (see
  // check_cache_file): `file` is made read-only and hard-linked there (a copy, read-only too,
  // across file systems), atomically (a temporary, then rename). A failure is the warning. Any
  // thread.
  void keep_file(const std::filesystem::path& path, const std::filesystem::path& file);
  int swept() const { return swept_; }  // temporaries removed

 private:
  void give_up(const std::string& problem);

  Warnings& warnings_;
  int lock_fd_ = -1;
  std::atomic<bool> writable_{true};
  int swept_ = 0;
};

}  // namespace tw::detail
