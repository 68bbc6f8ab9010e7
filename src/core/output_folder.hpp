#pragma once
// A pipeline's output folder, replaced as a whole: the files of a run appear all at once, the
// previous run's disappear with them, and the user's own files are left alone. Every file in it
// is a plain file, so cp -r, tar, rsync, git, Perforce or a zip carry the folder as it is.
//
// Layout (docs/robustness.md, "Output folder guarantee"):
//   <dir>/height.tif, report.json, placements/<x>.json, ...   the outputs, plain files
//   <dir>/.terraweave/outputs   the names of those outputs (the run's manifest, one a line)
//   <dir>/.terraweave/lock      flock'ed by the run writing here; holds its pid and start. Each
//                               new folder gets it as a hard link: always the same file
//   <dir>/.terraweave/plan/     a distributed run's plan (pipeline/job.hpp)
//   <parent>/.<name>.terraweave-staging-<pid>-<random>/   where a run writes the new folder
// The commit: the user's files (and .terraweave/plan) are hard-linked into the staging folder
// beside the run's outputs; then ONE renameat2(RENAME_EXCHANGE) swaps it with <dir>; then files
// the user created meanwhile are moved over, and the previous folder is deleted. So at every
// moment a reader sees exactly the files of one complete run, the old or the new.
// Fallbacks: a file system without RENAME_EXCHANGE (e.g. NFS) gets two renames (<dir> absent
// for an instant; a kill between them is repaired by the next command on <dir>). A folder that
// cannot be swapped (its parent not writable, a mount point, the current folder or one holding
// it) is committed in place: files renamed one by one from <dir>/.terraweave/commit-<token>,
// which the next command completes after a kill (each file old or new; the set mixed meanwhile).
// A folder of the older layout (outputs as symlinks into .terraweave/current) is migrated when
// first locked: each link is replaced by its file (same bytes), then the generations deleted.
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
  // holder's pid and start time, when another run holds it. Repairs what dead runs left.
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
  // Whether the commit swaps the folder (false: in place, see above). Decided on the first
  // stage() or commit().
  bool swaps() const { return mode_ == Mode::swap; }

 private:
  enum class Mode { undecided, swap, in_place };
  void prepare_staging();
  void commit_swap();
  void commit_in_place();

  std::filesystem::path dir_;   // as given
  std::filesystem::path real_;  // absolute, links resolved: what is swapped
  std::filesystem::path meta_;  // real_/.terraweave
  std::string token_;           // <pid>-<random>: names this run's entries
  Mode mode_ = Mode::undecided;
  StagedPath staging_;  // this run's folder until committed (empty: none)
  int lock_fd_ = -1;
  std::vector<std::filesystem::path> staged_;  // relative to dir_
  std::vector<std::filesystem::path> committed_;
};

// Test hook: when the environment variable TERRAWEAVE_TEST_PAUSE_AT equals `point`, prints
// "terraweave: paused at <point> (pid N)" to stderr and waits forever, so that a test kills
// the process there (SIGKILL) deterministically. Points: lock, stage:<k>, commit:<k>.
// TERRAWEAVE_TEST_NO_EXCHANGE=1 makes the commit take the fallback of a file system without
// RENAME_EXCHANGE.
void test_pause_point(const std::string& point);

}  // namespace tw
