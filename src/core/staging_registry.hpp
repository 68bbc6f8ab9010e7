#pragma once
// The paths being staged right now (OutputTransaction's temporary files, OutputFolder's staging
// folder), for an exit that skips their destructors: a library that cannot be loaded at its
// first call (cli/lazy_library.hpp) ends the process with _exit, from any thread and frame, and
// removes these first, so that a failed run leaves nothing half-written behind.
#include <filesystem>

namespace tw {

// Called by the stager when it creates a temporary, and when it renames or removes it. A path
// registered twice is removed from the registry once per unregister.
void register_staging(const std::filesystem::path& path);
void unregister_staging(const std::filesystem::path& path);

// Removes every registered file or folder (recursively) and empties the registry; errors are
// ignored. For an exit without unwinding (not async-signal-safe: it takes a mutex).
void remove_registered_staging() noexcept;

}  // namespace tw
