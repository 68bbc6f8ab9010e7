#include "core/staging_registry.hpp"

#include <mutex>
#include <set>

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

}  // namespace

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

void remove_registered_staging() noexcept {
  StagingRegistry& registry = staging_registry();
  const std::lock_guard lock(registry.mutex);
  for (const fs::path& path : registry.paths) {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  registry.paths.clear();
}

}  // namespace tw
