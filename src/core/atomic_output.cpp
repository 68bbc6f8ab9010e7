#include "core/atomic_output.hpp"

#include <unistd.h>

#include "core/error.hpp"
#include "core/staging_registry.hpp"

namespace tw {

namespace fs = std::filesystem;

OutputTransaction::~OutputTransaction() {
  std::error_code ignored;
  for (const auto& e : staged_) {
    fs::remove(e.temporary, ignored);
    unregister_staging(e.temporary);
  }
}

fs::path OutputTransaction::stage(const fs::path& final_path) {
  std::error_code ec;
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path(), ec);
  if (ec)
    fail("cannot create output folder {}: {}", final_path.parent_path().string(), ec.message());
  fs::path temporary = final_path;
  temporary.replace_filename("." + final_path.stem().string() + ".tmp" +
                             std::to_string(::getpid()) + final_path.extension().string());
  staged_.push_back({temporary, final_path});
  register_staging(temporary);
  return temporary;
}

void OutputTransaction::commit() {
  for (const auto& e : staged_) {
    if (!fs::exists(e.temporary)) fail("output {} was never written", e.final.string());
  }
  for (const auto& e : staged_) {
    std::error_code ec;
    fs::rename(e.temporary, e.final, ec);
    if (ec) fail("cannot move {} into place: {}", e.final.string(), ec.message());
    unregister_staging(e.temporary);
    committed_.push_back(e.final);
  }
  staged_.clear();
}

}  // namespace tw
