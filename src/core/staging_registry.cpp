#include "core/staging_registry.hpp"

#include <mutex>
#include <set>
#include <utility>

namespace tw {

namespace fs = std::filesystem;

namespace {

struct StagingRegistry {
  std::mutex mutex;
  std::multiset<fs::path> paths;
};

// Never destroyed: an exit from another thread may still find it after main returned.
StagingRegistry& staging_registry() {
  static auto* registry = new StagingRegistry;
  return *registry;
}

void register_staging(const fs::path& path) {
  StagingRegistry& registry = staging_registry();
  const std::lock_guard lock(registry.mutex);
  registry.paths.insert(path);
}

void unregister_staging(const fs::path& path) {
  StagingRegistry& registry = staging_registry();
  const std::lock_guard lock(registry.mutex);
  const auto it = registry.paths.find(path);
  if (it != registry.paths.end()) registry.paths.erase(it);
}

}  // namespace

void remove_registered_staging() noexcept {
  StagingRegistry& registry = staging_registry();
  const std::lock_guard lock(registry.mutex);
  for (const fs::path& path : registry.paths) {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  registry.paths.clear();
}

StagedPath::StagedPath(fs::path path) : path_(std::move(path)) {
  register_staging(path_);
}

StagedPath::~StagedPath() {
  remove();
}

StagedPath::StagedPath(StagedPath&& other) noexcept : path_(std::exchange(other.path_, {})) {}

StagedPath& StagedPath::operator=(StagedPath&& other) noexcept {
  if (this != &other) {
    remove();
    path_ = std::exchange(other.path_, {});
  }
  return *this;
}

void StagedPath::release() noexcept {
  if (path_.empty()) return;
  unregister_staging(path_);
  path_.clear();
}

void StagedPath::remove() noexcept {
  if (path_.empty()) return;
  std::error_code ignored;
  fs::remove_all(path_, ignored);
  release();
}

}  // namespace tw
