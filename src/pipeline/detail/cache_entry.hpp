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
#include <optional>
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

// The stat(2) facts of a cache file that its quick check compares (docs/cache.md, "The quick
// check"): not its change time nor its link count, which linking it into an output folder
// changes.
struct CacheFileStat {
  std::uint64_t bytes = 0;
  std::int64_t mtime_ns = 0;  // since the epoch
  std::uint64_t inode = 0, device = 0;
  bool operator==(const CacheFileStat&) const = default;
};

// A cache file's facts as an entry recorded them, and when (cache_clock_ns).
struct RecordedStat {
  CacheFileStat stat;
  std::int64_t recorded_ns = 0;
};

// The facts of `path` now; nullopt when it cannot be stat'ed.
std::optional<CacheFileStat> stat_cache_file(const std::filesystem::path& path);

// Now, in nanoseconds since the epoch: the clock of files' modification times.
std::int64_t cache_clock_ns();

// git's "racy" rule: facts recorded at `recorded_ns` vouch for the content only when the
// modification time lies before it by more than a timestamp's granularity (2 s, a FAT file
// system's). Otherwise the file could have been written again after they were taken, within the
// same timestamp, and its facts would not show it.
bool is_racy(const RecordedStat& recorded);

struct CacheFileCheck {
  CacheRead::State state = CacheRead::State::absent;
  std::string problem;  // for corrupt: what did not match
  bool hashed = false;  // read through: the recorded facts could not vouch for it
  CacheFileStat stat;   // for ok: its facts as checked, to record
};

// A file kept whole in the cache (a tile's output file, docs/cache.md): its own bytes, not a
// container, so that a reuse hard-links it into the output folder instead of copying. It is
// read-only, named by its content hash, and checked against `expected` before each reuse: an
// output file edited in place edits the cache file it is linked to, and that edit must never
// reach a later run. The quick check: when its facts now equal `recorded` and those are not
// racy, the recorded digest is trusted; otherwise the file is read through, its size and
// XXH3-128 compared. State::absent: no such file (pruned).
CacheFileCheck check_cache_file(const std::filesystem::path& path, const FileDigest& expected,
                                const std::optional<RecordedStat>& recorded);

// Places the checked cache file `path` at `target` (which must not exist): a hard link, or a
// copy where the two lie on different file systems (or links fail). Throws tw::Error naming
// `target` when neither works.
void place_cache_file(const std::filesystem::path& path, const std::filesystem::path& target);

// Marks an entry as used now (its modification time), so that pruning by age keeps what the
// latest runs used. Errors are ignored (a read-only cache still serves).
void touch_cache_entry(const std::filesystem::path& path);

// Marks a cache file as used now, or rather 3 s before now: out of the racy window of
// the entry recorded next (is_racy), so that its facts vouch for it from the next run on. A
// later write to the file, at the time it happens, shows in its modification time. Errors are
// ignored (a read-only cache still serves).
void settle_cache_file(const std::filesystem::path& path);

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
