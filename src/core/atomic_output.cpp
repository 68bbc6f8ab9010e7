#include "core/atomic_output.hpp"

#include <unistd.h>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

fs::path OutputTransaction::stage(const fs::path& final_path) {
  std::error_code ec;
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path(), ec);
  if (ec)
    fail("cannot create output folder {}: {}", final_path.parent_path().string(), ec.message());
  fs::path temporary = final_path;
  temporary.replace_filename("." + final_path.stem().string() + ".tmp" +
                             std::to_string(::getpid()) + final_path.extension().string());
  staged_.push_back({StagedPath(temporary), final_path});
  return temporary;
}

void OutputTransaction::commit() {
  for (const auto& e : staged_) {
    if (!fs::exists(e.temporary.path())) fail("output {} was never written", e.final.string());
  }
  for (auto& e : staged_) {
    std::error_code ec;
    fs::rename(e.temporary.path(), e.final, ec);
    if (ec) fail("cannot move {} into place: {}", e.final.string(), ec.message());
    e.temporary.release();
    committed_.push_back(e.final);
  }
  staged_.clear();
}

}  // namespace tw
