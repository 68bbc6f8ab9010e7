#include "pipeline/detail/cache_entry.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <random>
#include <span>

#include "core/content_hash.hpp"
#include "core/error.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'T', 'W', 'C', 'A', 'C', 'H', 'E', '1'};
constexpr std::size_t kHeaderBytes = 8 + 8 + 16;
constexpr std::int64_t kNanosPerSecond = 1'000'000'000;
// The coarsest timestamp the quick check allows for (FAT's 2 s; Linux file systems keep
// nanoseconds, from a clock a few milliseconds coarse).
constexpr std::int64_t kRacyWindowNs = 2 * kNanosPerSecond;
// How far before now a cache file's time is set when it is kept or marked used: out of the racy
// window of the entry recorded next.
constexpr std::int64_t kSettledAgeNs = kRacyWindowNs + kNanosPerSecond;

void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(char(v >> (8 * i)));
}

std::uint64_t get_u64(const std::string& in, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | std::uint8_t(in[at + std::size_t(i)]);
  return v;
}

ContentHash checksum(const std::string& payload) {
  return hash_bytes(std::as_bytes(std::span(payload.data(), payload.size())));
}

std::string unique_suffix() {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  return std::to_string(::getpid()) + "-" + std::to_string(random());
}

}  // namespace

void write_cache_entry(const fs::path& path, const CacheSections& sections) {
  std::string payload;
  for (const auto& [name, data] : sections) {
    put_u64(payload, name.size());
    payload += name;
    put_u64(payload, data.size());
    payload += data;
  }
  std::string file(kMagic, sizeof kMagic);
  put_u64(file, payload.size());
  const ContentHash sum = checksum(payload);
  put_u64(file, sum.high);
  put_u64(file, sum.low);
  file += payload;

  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) fail("cache: cannot create {}: {}", path.parent_path().string(), ec.message());
  const fs::path temporary =
      path.parent_path() / ("." + path.filename().string() + ".tmp" + unique_suffix());
  {
    errno = 0;
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(file.data(), std::streamsize(file.size()));
    out.close();
    if (!out) {
      // The reason (a full disk, no permission) is errno's: kept before remove() can change it.
      const std::string reason = errno ? std::strerror(errno) : "write failed";
      fs::remove(temporary, ec);
      fail("cache: cannot write {}: {}", temporary.string(), reason);
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    fail("cache: cannot rename {} to {}: {}", temporary.string(), path.string(), ec.message());
  }
}

CacheRead read_cache_entry(const fs::path& path) {
  CacheRead read;
  std::error_code ec;
  if (!fs::exists(path, ec)) return read;
  read.state = CacheRead::State::corrupt;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    read.problem = "unreadable";
    return read;
  }
  // One read of the whole entry (a character-by-character istreambuf_iterator copy was half
  // of a nothing-changed rerun's CPU: docs/performance.md, "The nightly floor").
  in.seekg(0, std::ios::end);
  const std::streamoff length = in.tellg();
  in.seekg(0, std::ios::beg);
  std::string file(std::size_t(std::max<std::streamoff>(length, 0)), '\0');
  if (!in || !in.read(file.data(), std::streamsize(file.size()))) {
    read.problem = "unreadable";
    return read;
  }
  if (file.size() < kHeaderBytes || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0) {
    read.problem = "not a terraweave cache entry";
    return read;
  }
  const std::uint64_t size = get_u64(file, 8);
  if (size != file.size() - kHeaderBytes) {
    read.problem = fmt::format("{} payload bytes, the header says {} (truncated?)",
                               file.size() - kHeaderBytes, size);
    return read;
  }
  const std::string payload = file.substr(kHeaderBytes);
  if (checksum(payload) != ContentHash{get_u64(file, 16), get_u64(file, 24)}) {
    read.problem = "checksum mismatch";
    return read;
  }
  std::size_t at = 0;
  auto field = [&](std::string& out) {
    if (payload.size() - at < 8) return false;
    const std::uint64_t n = get_u64(payload, at);
    at += 8;
    if (payload.size() - at < n) return false;
    out = payload.substr(at, std::size_t(n));
    at += std::size_t(n);
    return true;
  };
  while (at < payload.size()) {
    std::string name, data;
    if (!field(name) || !field(data)) {
      read.problem = "malformed sections";
      read.sections.clear();
      return read;
    }
    read.sections.emplace(std::move(name), std::move(data));
  }
  read.state = CacheRead::State::ok;
  return read;
}

std::optional<CacheFileStat> stat_cache_file(const fs::path& path) {
  struct ::stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return CacheFileStat{std::uint64_t(st.st_size),
                       std::int64_t(st.st_mtim.tv_sec) * kNanosPerSecond + st.st_mtim.tv_nsec,
                       std::uint64_t(st.st_ino), std::uint64_t(st.st_dev)};
}

std::int64_t cache_clock_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

bool is_racy(const RecordedStat& recorded) {
  return recorded.stat.mtime_ns >= recorded.recorded_ns - kRacyWindowNs;
}

CacheFileCheck check_cache_file(const fs::path& path, const FileDigest& expected,
                                const std::optional<RecordedStat>& recorded) {
  CacheFileCheck check;
  errno = 0;
  const std::optional<CacheFileStat> now = stat_cache_file(path);
  if (!now) {
    if (errno == ENOENT) return check;  // absent
    check.state = CacheRead::State::corrupt;
    check.problem = std::strerror(errno);
    return check;
  }
  check.stat = *now;
  check.state = CacheRead::State::corrupt;
  if (now->bytes != expected.bytes) {
    check.problem = fmt::format("{} bytes, the entry says {}", now->bytes, expected.bytes);
    return check;
  }
  if (recorded && recorded->stat == *now && !is_racy(*recorded)) {
    check.state = CacheRead::State::ok;
    return check;
  }
  check.hashed = true;
  try {
    if (file_digest(path).xxh3_128 != expected.xxh3_128) {
      check.problem = "content hash mismatch (edited through an output file linked to it?)";
      return check;
    }
  } catch (const Error& e) {
    check.problem = e.what();
    return check;
  }
  check.state = CacheRead::State::ok;
  return check;
}

void place_cache_file(const fs::path& path, const fs::path& target) {
  std::error_code ec;
  fs::create_hard_link(path, target, ec);
  if (!ec) return;
  const std::string link_problem = ec.message();
  ec.clear();
  fs::copy_file(path, target, ec);
  if (ec)
    fail("cannot write {} from the cache ({}; a link: {})", target.string(), ec.message(),
         link_problem);
}

void touch_cache_entry(const fs::path& path) {
  std::error_code ignored;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ignored);
}

void settle_cache_file(const fs::path& path) {
  const std::int64_t settled = cache_clock_ns() - kSettledAgeNs;
  const ::timespec times[2] = {
      {0, UTIME_OMIT}, {::time_t(settled / kNanosPerSecond), long(settled % kNanosPerSecond)}};
  ::utimensat(AT_FDCWD, path.c_str(), times, 0);  // errors ignored, as documented
}

void prepare_cache_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    fail("--cache {}: cannot create the folder{}", dir.string(), ec ? ": " + ec.message() : "");
  }
  const fs::path tag = dir / "CACHEDIR.TAG";
  if (fs::exists(tag, ec)) return;
  std::ofstream out(tag);
  out << "Signature: 8a477f597d28d172789f06886806bc55\n"
         "# This file is a cache directory tag created by terraweave (docs/cache.md).\n";
  if (!out) fail("--cache {}: cannot write {}", dir.string(), tag.string());
}

namespace {

// A temporary of write_cache_entry: ".<name>.twc.tmp<pid>-<n>".
bool is_cache_temporary(const fs::path& file) {
  const std::string name = file.filename().string();
  return name.starts_with(".") && name.find(".twc.tmp") != std::string::npos;
}

}  // namespace

CacheFolder::CacheFolder(const fs::path& dir, Warnings& warnings) : warnings_(warnings) {
  try {
    prepare_cache_dir(dir);
  } catch (const Error& e) {
    give_up(e.what());
    return;
  }
  const fs::path lock = dir / ".lock";
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) {
    give_up(fmt::format("--cache {}: cannot open {}: {}", dir.string(), lock.string(),
                        std::strerror(errno)));
    return;
  }
  // Alone (an exclusive lock granted at once): no other run writes here, so every temporary is
  // a killed run's. Then shared, as every run holds it.
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) == 0) {
    // Every folder, not a list of them: a store added later (synthesis/inputs was missed) is
    // swept too; only files named as temporaries are removed.
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      std::error_code removed;
      if (it->is_regular_file(removed) && is_cache_temporary(it->path()) &&
          fs::remove(it->path(), removed))
        ++swept_;
    }
  }
  ::flock(lock_fd_, LOCK_SH);
}

CacheFolder::~CacheFolder() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void CacheFolder::give_up(const std::string& problem) {
  if (writable_.exchange(false))
    warnings_.add("cache_unwritable", "cache", std::nullopt,
                  problem + "; the run goes on without storing in the cache");
}

void CacheFolder::write(const fs::path& path, const CacheSections& sections) {
  if (!writable_) return;
  try {
    write_cache_entry(path, sections);
  } catch (const Error& e) {
    give_up(e.what());
  }
}

void CacheFolder::keep_file(const fs::path& path, const fs::path& file) {
  if (!writable_) return;
  std::error_code ec;
  // Read-only before it is shared: the output file and the cache file are one inode.
  fs::permissions(file, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read, ec);
  if (!ec) fs::create_directories(path.parent_path(), ec);
  if (ec) {
    give_up(fmt::format("cache: cannot keep {}: {}", path.string(), ec.message()));
    return;
  }
  const fs::path temporary =
      path.parent_path() / ("." + path.filename().string() + ".tmp" + unique_suffix());
  fs::create_hard_link(file, temporary, ec);
  if (ec) {  // another file system: a copy, read-only like a link
    ec.clear();
    fs::copy_file(file, temporary, ec);
  }
  if (!ec) fs::rename(temporary, path, ec);
  std::error_code ignored;
  fs::remove(temporary, ignored);  // left by a rename onto a link of the same file (a no-op)
  if (ec) {
    give_up(
        fmt::format("cache: cannot keep {} as {}: {}", file.string(), path.string(), ec.message()));
  }
}

}  // namespace tw::detail
