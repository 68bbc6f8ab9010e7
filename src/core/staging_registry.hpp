#pragma once
// The paths being staged right now (OutputTransaction's temporary files, OutputFolder's staging
// folder, render-tile's tile files), for an exit that skips their destructors: a library that
// cannot be loaded at its first call (cli/lazy_library.hpp) ends the process with _exit, from
// any thread and frame, and removes these first, so that a failed run leaves nothing
// half-written behind.
#include <filesystem>

namespace tw {

// A temporary file or folder this process is writing: registered while a StagedPath holds it.
// release() once it was renamed into place (before the rename is reported as done); a
// StagedPath destroyed still holding its path removes it (recursively, errors ignored) and
// unregisters it. Each stager keeps its temporaries as StagedPaths: the one place that
// registers them.
class StagedPath {
 public:
  StagedPath() = default;  // holds nothing
  explicit StagedPath(std::filesystem::path path);
  ~StagedPath();
  StagedPath(StagedPath&& other) noexcept;
  StagedPath& operator=(StagedPath&& other) noexcept;  // removes the path it held
  StagedPath(const StagedPath&) = delete;
  StagedPath& operator=(const StagedPath&) = delete;

  const std::filesystem::path& path() const { return path_; }
  bool empty() const { return path_.empty(); }
  // Unregisters the path, which stays on disk, and holds nothing afterwards.
  void release() noexcept;
  // Removes the path (recursively, errors ignored), unregisters it; holds nothing afterwards.
  void remove() noexcept;

 private:
  std::filesystem::path path_;
};

// Removes every registered file or folder (recursively) and empties the registry; errors are
// ignored. For an exit without unwinding (not async-signal-safe: it takes a mutex).
void remove_registered_staging() noexcept;

}  // namespace tw
