#pragma once
// The check every command makes before it writes (issue #24: `export out --out out` deleted the
// run it exported, `area`/`grow --out RUN` replaced a run's files, `view RUN --out
// RUN/height.tif` replaced a layer with HTML): a command never writes over what it reads, nor
// into a folder another terraweave command writes as a whole (a run, an export, a plan: they
// hold `.terraweave/`), unless that is its documented job.
#include <filesystem>
#include <string>
#include <vector>

namespace tw {

// Whether terraweave writes `dir` as a whole (docs/robustness.md): it holds `.terraweave/`.
bool is_terraweave_folder(const std::filesystem::path& dir);

// Throws tw::Error naming `option` and what to do when `target` (the folder a command writes,
// or a file it writes, with `is_folder` false) is one of `inputs`, lies inside one of them or
// holds one of them; when the target folder is a run's (with `foreign_folders`); or when the
// target lies inside a folder terraweave writes as a whole. `allowed` names the one file a
// command may write into such a folder (view's RUN/view.html). Links are resolved, so another
// spelling changes nothing.
struct OutputGuard {
  std::string command{};  // "export", "area", ...: named in the message
  std::string option{};   // "--out"
  std::vector<std::filesystem::path> inputs{};
  bool foreign_folders = true;  // refuse a run's output folder as the target folder
  std::filesystem::path allowed{};
};
void require_safe_output(const std::filesystem::path& target, bool is_folder,
                         const OutputGuard& guard);

}  // namespace tw
