#include "core/output_guard.hpp"

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

fs::path resolved(const fs::path& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

// Whether `inner` is `outer` or lies below it.
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

bool is_terraweave_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / ".terraweave", ec);
}

void require_safe_output(const fs::path& target, bool is_folder, const OutputGuard& guard) {
  const fs::path out = resolved(target);
  if (!guard.allowed.empty() && out == resolved(guard.allowed)) return;
  for (const fs::path& input : guard.inputs) {
    const fs::path in = resolved(input);
    // A folder read (a run) may neither hold nor enclose the target; a file read may not be it.
    std::error_code dir_ec;
    const bool folder_read = fs::is_directory(in, dir_ec);
    if (out == in || (folder_read && within(out, in)) || within(in, out))
      fail("{} {} {}: {} what {} reads ({}); write to a folder of its own, beside it",
           guard.command, guard.option, target.string(),
           out == in ? "is" : (within(out, in) ? "lies inside" : "holds"), guard.command,
           input.string());
  }
  // A run's folder (report.json beside .terraweave/) as the target: its outputs would go. Any
  // folder terraweave writes as a whole (a run, an export, a plan) above the target: its next
  // commit would not know the file. The target folder of the same command is its job (an
  // export written again).
  std::error_code ec;
  if (is_folder && guard.foreign_folders && is_terraweave_folder(out) &&
      fs::exists(out / "report.json", ec))
    fail(
        "{} {} {}: is the output folder of a run, whose files it would replace or delete; "
        "write to a folder of its own (e.g. {}-{})",
        guard.command, guard.option, target.string(), target.string(), guard.command);
  for (fs::path dir = out.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (is_terraweave_folder(dir)) {
      fail(
          "{} {} {}: lies inside {}, a folder that terraweave writes as a whole (a run, an "
          "export or a plan) and would not keep it; write to a folder of its own",
          guard.command, guard.option, target.string(), dir.string());
    }
    if (dir == dir.root_path()) break;
  }
}

}  // namespace tw
