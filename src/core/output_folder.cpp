#include "core/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <random>
#include <regex>
#include <set>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMeta = ".terraweave";
constexpr const char* kCurrent = "current";

// The text of the link <dir>/<relative>: the way from its folder to .terraweave/current/<relative>.
fs::path link_target(const fs::path& relative) {
  fs::path target;
  for (const auto& part : relative.parent_path()) {
    if (!part.empty()) target /= "..";
  }
  return target / kMeta / kCurrent / relative;
}

// Regular files under `root`, relative to it.
std::vector<fs::path> files_under(const fs::path& root) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec)) files.push_back(it->path().lexically_relative(root));
  }
  return files;
}

std::string current_generation(const fs::path& meta) {
  std::error_code ec;
  const fs::path target = fs::read_symlink(meta / kCurrent, ec);
  return ec ? std::string() : target.string();
}

int generation_number(const std::string& generation) {
  if (!generation.starts_with("gen-")) return 0;
  return std::atoi(generation.c_str() + 4);
}

// A temporary of an older terraweave (".height.tmp<pid>.exr", written beside the outputs)
// whose process is gone. Only names a pipeline wrote: the layers, the report, placements.
bool is_dead_legacy_temporary(const fs::path& relative) {
  static const std::regex pattern(
      R"((\.(height|splat|avoidance|preview|report)|placements/\.[A-Za-z0-9_-]+))"
      R"(\.tmp([0-9]+)\.(exr|tif|png|json))");
  std::smatch match;
  const std::string name = relative.generic_string();
  if (!std::regex_match(name, match, pattern)) return false;
  const long pid = std::atol(match[3].str().c_str());
  return pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
}

// Deletes our links in <dir>/<folder> that resolve to nothing (outputs of no complete run) and
// dead runs' temporaries of older versions, then the folder itself when that leaves it empty.
// Never follows a link out of the folder.
void delete_dangling_links(const fs::path& dir, const fs::path& folder) {
  const fs::path path = dir / folder;
  std::error_code ec;
  if (fs::is_symlink(path, ec) || !fs::is_directory(path, ec)) return;
  std::vector<fs::path> dangling;
  for (auto it = fs::directory_iterator(path, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    std::error_code entry_ec;
    if (it->symlink_status(entry_ec).type() == fs::file_type::regular &&
        is_dead_legacy_temporary(folder / it->path().filename())) {
      dangling.push_back(it->path());
    }
    if (!it->is_symlink(entry_ec)) continue;
    const fs::path relative = folder / it->path().filename();
    if (fs::read_symlink(it->path(), entry_ec) != link_target(relative)) continue;  // not ours
    if (!fs::exists(it->path(), entry_ec)) dangling.push_back(it->path());
  }
  for (const fs::path& link : dangling) fs::remove(link, ec);
  if (!folder.empty() && fs::is_empty(path, ec)) fs::remove(path, ec);
}

// What runs no longer alive left (the caller holds the lock): every generation but the current
// one, every staging entry, and in the folders any generation used, links that resolve to
// nothing and older versions' temporaries.
void delete_stale(const fs::path& dir, const fs::path& meta) {
  const std::string current = current_generation(meta);
  std::set<fs::path> folders{fs::path()};
  std::vector<fs::path> stale;
  std::error_code ec;
  for (auto it = fs::directory_iterator(meta, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!(name.starts_with("gen-") || name.starts_with("staging-"))) continue;
    std::error_code entry_ec;
    if (it->symlink_status(entry_ec).type() == fs::file_type::directory) {
      for (const fs::path& file : files_under(it->path())) folders.insert(file.parent_path());
    }
    if (name != current) stale.push_back(it->path());
  }
  for (const fs::path& path : stale) fs::remove_all(path, ec);
  for (const fs::path& folder : folders) delete_dangling_links(dir, folder);
}

std::string holder_line() {
  char started[32];
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(started, sizeof started, "%Y-%m-%d %H:%M:%S UTC", &utc);
  return fmt::format("pid {}, started {}", ::getpid(), started);
}

std::string read_holder(int fd) {
  char buffer[256];
  const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
  std::string line(buffer, n > 0 ? std::size_t(n) : 0);
  if (const auto end = line.find('\n'); end != std::string::npos) line.resize(end);
  return line.empty() ? "holder unknown" : line;
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir) : dir_(std::move(dir)), meta_(dir_ / kMeta) {
  std::error_code ec;
  fs::create_directories(meta_, ec);
  if (ec) fail("cannot create output folder {}: {}", meta_.string(), ec.message());
  const fs::path lock = meta_ / "lock";
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) fail("cannot open {}: {}", lock.string(), std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string holder = read_holder(lock_fd_);
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK) {
      fail(
          "output folder {} is in use by another terraweave run ({}); wait for it to finish or "
          "choose another --out",
          dir_.string(), holder);
    }
    fail("cannot lock {}: {}", lock.string(), std::strerror(error));
  }
  // The holder line only serves a second run's message: failing to write it is no error.
  const std::string holder = holder_line() + "\n";
  if (::ftruncate(lock_fd_, 0) == 0) (void)!::pwrite(lock_fd_, holder.data(), holder.size(), 0);
  delete_stale(dir_, meta_);
  test_pause_point("lock");
}

std::unique_ptr<OutputFolder> OutputFolder::lock_if_used(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir / kMeta, ec)) return nullptr;
  return std::make_unique<OutputFolder>(dir);
}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

fs::path OutputFolder::stage(const fs::path& final_path) {
  const fs::path relative =
      final_path.lexically_normal().lexically_relative(dir_.lexically_normal());
  const bool inside = !relative.empty() && relative.is_relative() && *relative.begin() != ".." &&
                      *relative.begin() != "." && *relative.begin() != kMeta;
  if (!inside) {
    fail("output {} is outside the output folder {}", final_path.string(), dir_.string());
  }
  for (const fs::path& staged : staged_) {
    if (staged == relative) fail("output {} is written twice", final_path.string());
  }
  test_pause_point(fmt::format("stage:{}", staged_.size()));
  std::error_code ec;
  if (staging_.empty()) {
    std::random_device random;
    token_ = fmt::format("staging-{}-{:08x}", ::getpid(), random());
    staging_ = meta_ / token_;
  }
  fs::create_directories((staging_ / relative).parent_path(), ec);
  if (ec) fail("cannot create {}: {}", (staging_ / relative).parent_path().string(), ec.message());
  staged_.push_back(relative);
  return staging_ / relative;
}

std::vector<std::pair<fs::path, fs::path>> OutputFolder::staged_files() const {
  std::vector<std::pair<fs::path, fs::path>> files;
  for (const fs::path& relative : staged_) files.emplace_back(relative, staging_ / relative);
  return files;
}

void OutputFolder::commit() {
  int step = 0;
  const auto pause = [&step] { test_pause_point(fmt::format("commit:{}", step++)); };
  pause();
  std::error_code ec;
  for (const fs::path& relative : staged_) {
    if (!fs::is_regular_file(staging_ / relative, ec)) {
      fail("output {} was never written", (dir_ / relative).string());
    }
  }
  // 1. The complete run becomes a generation (not yet the current one).
  const std::string generation =
      fmt::format("gen-{}", generation_number(current_generation(meta_)) + 1);
  if (staging_.empty()) {
    token_ = fmt::format("staging-{}-empty", ::getpid());
    staging_ = meta_ / token_;
    fs::create_directories(staging_, ec);
  }
  fs::rename(staging_, meta_ / generation, ec);
  if (ec) fail("cannot rename {} to {}: {}", staging_.string(), generation, ec.message());
  staging_ = meta_ / generation;  // deleted by the destructor until it is current
  pause();
  // 2. A link for every name; one the previous run wrote is there already. A new link resolves
  // to nothing until the swap, so the name still reads as absent.
  const fs::path new_link = meta_ / (token_ + ".link");
  for (const fs::path& relative : staged_) {
    const fs::path link = dir_ / relative;
    const fs::path target = link_target(relative);
    if (fs::is_symlink(link, ec) && fs::read_symlink(link, ec) == target) continue;
    fs::create_directories(link.parent_path(), ec);
    if (ec) fail("cannot create {}: {}", link.parent_path().string(), ec.message());
    fs::remove(new_link, ec);
    fs::create_symlink(target, new_link, ec);
    if (ec) fail("cannot create a link in {}: {}", meta_.string(), ec.message());
    fs::rename(new_link, link, ec);  // replaces a file of an older terraweave, never a folder
    if (ec) fail("cannot replace {}: {}", link.string(), ec.message());
    pause();
  }
  // 3. The swap: one rename(2) of `current` makes the new run the folder's outputs.
  const fs::path new_current = meta_ / (token_ + ".current");
  fs::remove(new_current, ec);
  fs::create_symlink(generation, new_current, ec);
  if (ec) fail("cannot create a link in {}: {}", meta_.string(), ec.message());
  fs::rename(new_current, meta_ / kCurrent, ec);
  if (ec) fail("cannot make {} current: {}", generation, ec.message());
  staging_.clear();
  for (const fs::path& relative : staged_) committed_.push_back(dir_ / relative);
  pause();
  // 4. The previous generation, and the links of its files this run did not write.
  delete_stale(dir_, meta_);
  pause();
}

void test_pause_point(const std::string& point) {
  static const char* const wanted = std::getenv("TERRAWEAVE_TEST_PAUSE_AT");
  if (wanted == nullptr || point != wanted) return;
  std::fprintf(stderr, "terraweave: paused at %s (pid %d)\n", point.c_str(), int(::getpid()));
  std::fflush(stderr);
  for (;;) ::pause();
}

}  // namespace tw
