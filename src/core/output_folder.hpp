#pragma once
// A pipeline's output folder, replaced as a whole: the files of a run appear all at once, the
// previous run's disappear with them, and the user's own files are left alone.
//
// Layout (docs/robustness.md, "Output folder guarantee"):
//   <dir>/.terraweave/lock            flock'ed by the run writing here; holds its pid and start
//   <dir>/.terraweave/staging-<pid>-<random>/   where a run writes every file
//   <dir>/.terraweave/gen-<N>/        a complete run (the staging folder, renamed when complete)
//   <dir>/.terraweave/current         symlink -> gen-<N>: THE commit is one rename(2) of it
//   <dir>/<name>                      symlink -> .terraweave/current/<name>, for height.tif,
//                                     report.json, placements/<x>.json, ...
// Before the swap of `current`, every name the new run produces already has its link (one that
// does not resolve yet reads as absent); after it, the previous run's links that no longer
// resolve, and its generation, are deleted. So at every moment a reader sees, through the
// links, exactly the files of one complete run, the old or the new, and report.json names
// exactly those. A killed run leaves only .terraweave/ entries (and links that resolve to
// nothing); the next run, holding the lock (so no other run is alive), deletes them, and the
// temporaries an older terraweave left beside its outputs (.height.tmp<pid>.exr, dead pid).
// Not fsync'ed: the guarantee holds against kills, not against a power loss.
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_output.hpp"

namespace tw {

class OutputFolder final : public OutputStager {
 public:
  // Takes the folder's lock, creating <dir> and <dir>/.terraweave; fails at once, naming the
  // holder's pid and start time, when another run holds it. Deletes what dead runs left.
  explicit OutputFolder(std::filesystem::path dir);
  // The same, but only when terraweave has written into `dir` before (else nullptr): a run
  // locks early without creating anything in a folder it may never write to.
  static std::unique_ptr<OutputFolder> lock_if_used(const std::filesystem::path& dir);
  ~OutputFolder() override;  // deletes an uncommitted staging folder, releases the lock
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where to write instead of `final_path`, which must lie inside the folder (outside, or
  // under .terraweave, is an error naming it): the same relative path in the staging folder.
  std::filesystem::path stage(const std::filesystem::path& final_path) override;
  // Makes the staged files the folder's outputs (see above). Fails naming a file never written.
  void commit();
  // The files staged so far, relative to the folder, and where each was written.
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_files() const;
  const std::vector<std::filesystem::path>& committed() const { return committed_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path meta_;     // dir_/.terraweave
  std::string token_;              // staging-<pid>-<random>: names this run's entries
  std::filesystem::path staging_;  // this run's folder until it is current (empty: none)
  int lock_fd_ = -1;
  std::vector<std::filesystem::path> staged_;  // relative to dir_
  std::vector<std::filesystem::path> committed_;
};

// Test hook: when the environment variable TERRAWEAVE_TEST_PAUSE_AT equals `point`, prints
// "terraweave: paused at <point> (pid N)" to stderr and waits forever, so that a test kills
// the process there (SIGKILL) deterministically. Points: lock, stage:<k>, commit:<k>.
void test_pause_point(const std::string& point);

}  // namespace tw
