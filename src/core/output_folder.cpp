#include "core/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2 (glibc 2.28)
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <random>
#include <regex>
#include <set>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMeta = ".terraweave";
constexpr const char* kManifestHeader = "terraweave outputs";

using Names = std::set<fs::path>;

// ---- names -------------------------------------------------------------------------------------

// Siblings of the folder: .<name>.terraweave-staging-<token> and -previous-<token>.
fs::path sibling(const fs::path& real, const std::string& kind, const std::string& token) {
  return real.parent_path() /
         ("." + real.filename().string() + ".terraweave-" + kind + "-" + token);
}

// The token of a sibling of `real` of this kind, or "" when `entry` is none.
std::string sibling_token(const fs::path& real, const std::string& kind, const fs::path& entry) {
  const std::string prefix = "." + real.filename().string() + ".terraweave-" + kind + "-";
  const std::string name = entry.filename().string();
  static const std::regex token(R"([0-9]+-[0-9a-f]{8})");
  if (!name.starts_with(prefix) || !std::regex_match(name.substr(prefix.size()), token)) return {};
  return name.substr(prefix.size());
}

// Entries of .terraweave/ that belong to one run and never travel to the next folder: the
// manifest, the lock (linked, not copied), staging and commit folders of the in-place commit,
// and what the older layout kept there (current, gen-<N>, *.link, *.current).
bool is_bookkeeping(const fs::path& relative) {
  auto part = relative.begin();
  if (part == relative.end() || *part != kMeta) return false;
  if (++part == relative.end()) return false;  // .terraweave itself
  const std::string name = part->string();
  return name == "outputs" || name == "lock" || name == "current" || name.starts_with("gen-") ||
         name.starts_with("staging-") || name.starts_with("commit-") || name.ends_with(".link") ||
         name.ends_with(".current");
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

// Regular files under `root`, relative to it (links not followed).
std::vector<fs::path> files_under(const fs::path& root) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code entry_ec;
    if (it->symlink_status(entry_ec).type() == fs::file_type::regular)
      files.push_back(it->path().lexically_relative(root));
  }
  return files;
}

bool lexists(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type() != fs::file_type::not_found && !ec;
}

// ---- the manifest: <folder>/.terraweave/outputs -------------------------------------------------

struct Manifest {
  std::string token;  // the run that wrote the folder
  Names outputs;
};

Manifest read_manifest(const fs::path& file) {
  Manifest manifest;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line) || !line.starts_with(kManifestHeader)) return manifest;
  manifest.token = line.substr(std::min(line.size(), std::strlen(kManifestHeader) + 1));
  while (std::getline(in, line))
    if (!line.empty()) manifest.outputs.insert(fs::path(line));
  return manifest;
}

void write_manifest(const fs::path& file, const std::string& token, const Names& outputs) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  std::ofstream out(file, std::ios::trunc);
  out << kManifestHeader << ' ' << token << '\n';
  for (const fs::path& name : outputs) {
    const std::string text = name.generic_string();
    if (text.find('\n') != std::string::npos) fail("output name {} holds a line break", text);
    out << text << '\n';
  }
  out.close();
  if (!out) fail("cannot write {}", file.string());
}

// ---- moving the user's files between folders ---------------------------------------------------

// Recreates in `to` what the user keeps in `from` (everything but `skip`, the bookkeeping and dead
// temporaries): folders made, files hard-linked (copied where links fail), links copied as links.
// An entry whose name `to` already holds (a new output) is not carried: the run's file wins.
void carry(const fs::path& from, const fs::path& to, const Names& skip, const fs::path& relative) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(from / relative, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const fs::path name = relative / it->path().filename();
    if (skip.contains(name) || is_bookkeeping(name) || is_dead_legacy_temporary(name)) continue;
    std::error_code entry_ec;
    const fs::file_type type = it->symlink_status(entry_ec).type();
    const fs::path target = to / name;
    const fs::file_type there = fs::symlink_status(target, entry_ec).type();
    if (type == fs::file_type::directory) {
      if (there != fs::file_type::not_found && there != fs::file_type::directory) continue;
      const bool made = there == fs::file_type::not_found;
      if (made && !fs::create_directory(target, entry_ec))
        fail("cannot create {}: {}", target.string(), entry_ec.message());
      carry(from, to, skip, name);
      // A folder that held only outputs of the previous run goes with them.
      if (made && fs::is_empty(target, entry_ec) && !fs::is_empty(it->path(), entry_ec))
        fs::remove(target, entry_ec);
      continue;
    }
    if (there != fs::file_type::not_found) continue;
    if (type == fs::file_type::regular) {
      fs::create_hard_link(it->path(), target, entry_ec);
      if (entry_ec) fs::copy_file(it->path(), target, entry_ec);
    } else if (type == fs::file_type::symlink) {
      fs::copy_symlink(it->path(), target, entry_ec);
    } else {
      continue;  // a socket or FIFO: nothing to carry
    }
    if (entry_ec) fail("cannot keep {}: {}", (from / name).string(), entry_ec.message());
  }
}

// After the swap: what the user created in the previous folder `from` since it was carried
// (absent from `to`, not an output of the previous run) is moved over.
void move_late_files(const fs::path& from, const fs::path& to, const Names& previous_outputs,
                     const fs::path& relative) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(from / relative, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const fs::path name = relative / it->path().filename();
    if (previous_outputs.contains(name) || is_bookkeeping(name)) continue;
    std::error_code entry_ec;
    const fs::file_type there = fs::symlink_status(to / name, entry_ec).type();
    if (there == fs::file_type::not_found) {
      fs::rename(it->path(), to / name, entry_ec);
    } else if (there == fs::file_type::directory &&
               it->symlink_status(entry_ec).type() == fs::file_type::directory) {
      move_late_files(from, to, previous_outputs, name);
    }
  }
}

// Deletes the folder `folder` holding a previous run once its late files are moved to `real`.
void retire_previous(const fs::path& folder, const fs::path& real) {
  const Manifest previous = read_manifest(folder / kMeta / "outputs");
  move_late_files(folder, real, previous.outputs, fs::path());
  std::error_code ec;
  fs::remove_all(folder, ec);
}

// Deletes <real>/<name> and then its parent folders that this leaves empty, up to <real>.
void remove_output(const fs::path& real, const fs::path& name) {
  std::error_code ec;
  if (fs::symlink_status(real / name, ec).type() == fs::file_type::directory) return;
  fs::remove(real / name, ec);
  for (fs::path folder = name.parent_path(); !folder.empty(); folder = folder.parent_path()) {
    if (!fs::is_empty(real / folder, ec) || ec) break;
    fs::remove(real / folder, ec);
  }
}

// ---- the in-place commit: <real>/.terraweave/commit-<token>/ ------------------------------------

// Completes an in-place commit (also one a killed run left): every new output renamed into
// place, then the manifest, then the previous run's outputs the new one did not write deleted.
void roll_forward(const fs::path& real, const fs::path& journal,
                  const std::function<void()>& after_each_file) {
  const Manifest next = read_manifest(journal / kMeta / "outputs");
  const Manifest previous = read_manifest(journal / kMeta / "previous-outputs");
  std::error_code ec;
  for (const fs::path& name : next.outputs) {
    if (!lexists(journal / name)) continue;  // moved before a kill
    fs::create_directories((real / name).parent_path(), ec);
    if (fs::symlink_status(real / name, ec).type() == fs::file_type::directory)
      fail("cannot write {}: a folder has that name", (real / name).string());
    fs::rename(journal / name, real / name, ec);
    if (ec) fail("cannot move {} into place: {}", (real / name).string(), ec.message());
    after_each_file();
  }
  if (lexists(journal / kMeta / "outputs")) {
    fs::rename(journal / kMeta / "outputs", real / kMeta / "outputs", ec);
    if (ec) fail("cannot write {}: {}", (real / kMeta / "outputs").string(), ec.message());
  }
  for (const fs::path& name : previous.outputs)
    if (!next.outputs.contains(name)) remove_output(real, name);
  fs::remove_all(journal, ec);
}

// ---- the older layout: outputs as links into .terraweave/current -------------------------------

// The text of the older layout's link <dir>/<relative>.
fs::path legacy_link_target(const fs::path& relative) {
  fs::path target;
  for (const auto& part : relative.parent_path()) {
    if (!part.empty()) target /= "..";
  }
  return target / kMeta / "current" / relative;
}

// Replaces each link of the current generation by its file (the same bytes, one rename each, so
// a reader sees no change), writes the manifest, then deletes the generations and the older
// layout's links that resolve to nothing. A kill on the way leaves what the next lock resumes.
void migrate_legacy(const fs::path& real) {
  const fs::path meta = real / kMeta;
  std::error_code ec;
  const fs::path current = fs::read_symlink(meta / "current", ec);
  if (ec) return;  // not the older layout
  Names outputs;
  for (const fs::path& name : files_under(meta / current)) {
    const fs::path file = meta / current / name;
    const fs::path link = real / name;
    std::error_code link_ec;
    if (fs::read_symlink(link, link_ec) != legacy_link_target(name)) {
      // Replaced by its file before a kill (same inode), or by the user since: not an output.
      if (fs::equivalent(link, file, link_ec)) outputs.insert(name);
      continue;
    }
    const fs::path temporary = meta / ("migrate-" + std::to_string(::getpid()) + ".link");
    fs::remove(temporary, link_ec);
    fs::create_hard_link(file, temporary, link_ec);
    if (link_ec) fs::copy_file(file, temporary, link_ec);
    if (!link_ec) fs::rename(temporary, link, link_ec);
    if (link_ec) fail("cannot turn {} into a plain file: {}", link.string(), link_ec.message());
    outputs.insert(name);
  }
  write_manifest(meta / "outputs.new", "migrated", outputs);
  fs::rename(meta / "outputs.new", meta / "outputs", ec);
  fs::remove(meta / "current", ec);
  // The older layout's links left that resolve to nothing, anywhere in the folder.
  std::vector<fs::path> dangling;
  for (auto it = fs::recursive_directory_iterator(real, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::path name = it->path().lexically_relative(real);
    if (name == kMeta) {
      it.disable_recursion_pending();
      continue;
    }
    std::error_code entry_ec;
    if (it->is_symlink(entry_ec) &&
        fs::read_symlink(it->path(), entry_ec) == legacy_link_target(name) &&
        !fs::exists(it->path(), entry_ec))
      dangling.push_back(name);
  }
  for (const fs::path& name : dangling) remove_output(real, name);
  for (auto it = fs::directory_iterator(meta, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    if (is_bookkeeping(fs::path(kMeta) / it->path().filename()) &&
        it->path().filename() != "lock" && it->path().filename() != "outputs") {
      std::error_code entry_ec;
      fs::remove_all(it->path(), entry_ec);
    }
  }
}

// ---- the lock -----------------------------------------------------------------------------------

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

bool same_file(int fd, const fs::path& path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

// A run killed between the two renames of the fallback swap left no folder: the complete new
// one is its staging sibling (the previous one beside it). Puts it in place, under its lock.
void restore_absent_folder(const fs::path& dir) {
  const fs::path real = fs::absolute(dir).lexically_normal();
  if (lexists(real) || real.filename().empty()) return;
  std::error_code ec;
  for (auto it = fs::directory_iterator(real.parent_path(), ec);
       !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string token = sibling_token(real, "previous", it->path());
    if (token.empty()) continue;
    const fs::path staging = sibling(real, "staging", token);
    if (read_manifest(staging / kMeta / "outputs").token != token) continue;
    const int fd = ::open((staging / kMeta / "lock").c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    ::flock(fd, LOCK_EX);  // a live run is between its two renames: a moment
    std::error_code rename_ec;
    if (!lexists(real) && lexists(staging)) fs::rename(staging, real, rename_ec);
    ::close(fd);
    return;
  }
}

// Whether the process's current folder is `real` or inside it (the folder cannot be swapped
// from under the shell or program sitting in it).
bool holds_current_folder(const fs::path& real) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return false;
  const fs::path relative = cwd.lexically_relative(real);
  return !relative.empty() && *relative.begin() != "..";
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir) : dir_(std::move(dir)) {
  restore_absent_folder(dir_);
  std::error_code ec;
  fs::create_directories(dir_ / kMeta, ec);
  if (ec) fail("cannot create output folder {}: {}", (dir_ / kMeta).string(), ec.message());
  real_ = fs::canonical(dir_, ec);
  if (ec) fail("cannot resolve output folder {}: {}", dir_.string(), ec.message());
  meta_ = real_ / kMeta;
  const fs::path lock = meta_ / "lock";
  // The lock file is the same file in every folder a swap puts here (a hard link); a run that
  // opened it just as the folder changed checks it still is, and opens it again if not.
  for (int attempt = 0; lock_fd_ < 0; ++attempt) {
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
    if (!same_file(lock_fd_, lock) && attempt < 10) {
      ::close(lock_fd_);
      lock_fd_ = -1;
    }
  }
  // The holder line only serves a second run's message: failing to write it is no error.
  const std::string holder = holder_line() + "\n";
  if (::ftruncate(lock_fd_, 0) == 0) (void)!::pwrite(lock_fd_, holder.data(), holder.size(), 0);
  std::random_device random;
  token_ = fmt::format("{}-{:08x}", ::getpid(), random());

  // Holding the lock, no other run is alive here: repair and delete what dead ones left.
  migrate_legacy(real_);
  const std::string shown = read_manifest(meta_ / "outputs").token;
  for (auto it = fs::directory_iterator(meta_, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with("commit-")) roll_forward(real_, it->path(), [] {});
    if (name.starts_with("staging-")) fs::remove_all(it->path(), ec);
  }
  ec.clear();
  if (!real_.parent_path().empty() && real_ != real_.root_path()) {
    for (auto it = fs::directory_iterator(real_.parent_path(), ec);
         !ec && it != fs::directory_iterator(); it.increment(ec)) {
      std::error_code entry_ec;
      if (const std::string t = sibling_token(real_, "previous", it->path()); !t.empty()) {
        retire_previous(it->path(), real_);
      } else if (const std::string s = sibling_token(real_, "staging", it->path()); !s.empty()) {
        // After the exchange (the folder shows that run) it holds the previous folder.
        if (s == shown) {
          retire_previous(it->path(), real_);
        } else {
          fs::remove_all(it->path(), entry_ec);
        }
      }
    }
  }
  ec.clear();
  for (const fs::path& folder : {fs::path(), fs::path("placements")}) {
    for (auto it = fs::directory_iterator(real_ / folder, ec);
         !ec && it != fs::directory_iterator(); it.increment(ec)) {
      std::error_code entry_ec;
      if (it->symlink_status(entry_ec).type() == fs::file_type::regular &&
          is_dead_legacy_temporary(folder / it->path().filename()))
        fs::remove(it->path(), entry_ec);
    }
    ec.clear();
  }
  test_pause_point("lock");
}

std::unique_ptr<OutputFolder> OutputFolder::lock_if_used(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir / kMeta, ec)) return nullptr;
  return std::make_unique<OutputFolder>(dir);
}

OutputFolder::~OutputFolder() {
  staging_.remove();  // while the lock is held
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void OutputFolder::prepare_staging() {
  if (mode_ != Mode::undecided) return;
  std::error_code ec;
  struct stat folder {
  }, parent{};
  const bool swappable = !real_.parent_path().empty() && real_ != real_.root_path() &&
                         !holds_current_folder(real_) && ::stat(real_.c_str(), &folder) == 0 &&
                         ::stat(real_.parent_path().c_str(), &parent) == 0 &&
                         folder.st_dev == parent.st_dev;  // else a mount point
  if (swappable) {
    // The staging folder beside; it needs a writable parent, and hard links for the lock.
    const fs::path staging = sibling(real_, "staging", token_);
    if (fs::create_directories(staging / kMeta, ec) && !ec) {
      fs::create_hard_link(meta_ / "lock", staging / kMeta / "lock", ec);
      if (!ec) {
        staging_ = StagedPath(staging);
        mode_ = Mode::swap;
        return;
      }
    }
    std::error_code ignored;
    fs::remove_all(staging, ignored);
  }
  staging_ = StagedPath(meta_ / ("staging-" + token_));  // first: a partial folder goes too
  fs::create_directories(staging_.path(), ec);
  if (ec) fail("cannot create {}: {}", staging_.path().string(), ec.message());
  mode_ = Mode::in_place;
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
  prepare_staging();
  std::error_code ec;
  fs::create_directories((staging_.path() / relative).parent_path(), ec);
  if (ec)
    fail("cannot create {}: {}", (staging_.path() / relative).parent_path().string(), ec.message());
  staged_.push_back(relative);
  return staging_.path() / relative;
}

std::vector<std::pair<fs::path, fs::path>> OutputFolder::staged_files() const {
  std::vector<std::pair<fs::path, fs::path>> files;
  for (const fs::path& relative : staged_) files.emplace_back(relative, staging_.path() / relative);
  return files;
}

void OutputFolder::commit() {
  test_pause_point("commit:0");
  prepare_staging();
  std::error_code ec;
  for (const fs::path& relative : staged_) {
    if (!fs::is_regular_file(staging_.path() / relative, ec)) {
      fail("output {} was never written", (dir_ / relative).string());
    }
  }
  if (mode_ == Mode::swap) {
    commit_swap();
  } else {
    commit_in_place();
  }
  for (const fs::path& relative : staged_) committed_.push_back(dir_ / relative);
}

// 1. the staging folder gets the manifest and the user's files; 2. one renameat2 exchange (or,
// without it, two renames); 3. files the user made meanwhile are moved; the previous folder goes.
void OutputFolder::commit_swap() {
  int step = 1;
  const auto pause = [&step] { test_pause_point(fmt::format("commit:{}", step++)); };
  const Names outputs(staged_.begin(), staged_.end());
  write_manifest(staging_.path() / kMeta / "outputs", token_, outputs);
  Names skip = read_manifest(meta_ / "outputs").outputs;
  skip.insert(outputs.begin(), outputs.end());
  carry(real_, staging_.path(), skip, fs::path());
  pause();  // commit:1, complete beside the folder
  static const bool no_exchange = std::getenv("TERRAWEAVE_TEST_NO_EXCHANGE") != nullptr;
  int swapped = no_exchange ? -1
                            : ::renameat2(AT_FDCWD, staging_.path().c_str(), AT_FDCWD,
                                          real_.c_str(), RENAME_EXCHANGE);
  const int error = errno;
  std::error_code ec;
  fs::path previous = staging_.path();  // after the exchange, the previous folder is there
  if (swapped != 0) {
    if (!no_exchange && error != EINVAL && error != ENOSYS && error != EOPNOTSUPP)
      fail("cannot swap {} into place: {}", real_.string(), std::strerror(error));
    // The fallback: the folder is absent between the two renames.
    previous = sibling(real_, "previous", token_);
    fs::rename(real_, previous, ec);
    if (ec) fail("cannot move {} aside: {}", real_.string(), ec.message());
    pause();  // commit:2, no folder (the next command puts the new one in place)
    fs::rename(staging_.path(), real_, ec);
    if (ec) fail("cannot move {} into place: {}", real_.string(), ec.message());
  }
  staging_.release();
  pause();  // the new run is the folder's
  retire_previous(previous, real_);
  pause();
}

// The manifests go into the staging folder, which is renamed commit-<token> (from then on the
// commit completes, by this run or the next command), then every file is renamed into place.
void OutputFolder::commit_in_place() {
  int step = 1;
  const auto pause = [&step] { test_pause_point(fmt::format("commit:{}", step++)); };
  const Names outputs(staged_.begin(), staged_.end());
  const Manifest previous = read_manifest(meta_ / "outputs");
  write_manifest(staging_.path() / kMeta / "previous-outputs", previous.token, previous.outputs);
  write_manifest(staging_.path() / kMeta / "outputs", token_, outputs);
  pause();  // commit:1
  const fs::path journal = meta_ / ("commit-" + token_);
  std::error_code ec;
  fs::rename(staging_.path(), journal, ec);
  if (ec) fail("cannot rename {}: {}", staging_.path().string(), ec.message());
  staging_.release();
  pause();  // commit:2
  roll_forward(real_, journal, pause);
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
