#pragma once
// A shared library the program loads on its first call (TERRAWEAVE_LAZY_GDAL: GDAL, and
// cpp-httplib for `view --serve`; docs/performance.md, "GDAL on first use"). The build writes
// one stub per function of the library that the program calls (cmake/lazy_library_stubs.py,
// build/generated/<prefix>_stubs.S): each jumps through a slot, and a slot first leads to
// `<prefix>_resolve(index)`, which calls resolve_lazy below with the stubs' tables and jumps to
// what it returns with the caller's arguments.
#include <atomic>
#include <cstddef>
#include <mutex>

namespace tw {

struct LazyLibrary {
  const char* what;      // for the error line: "GDAL"
  const char* variable;  // the environment variable that names another file
  const char* soname;    // the stubs' tables
  void** slots;
  const char* const* names;
  std::size_t count;
  void (*on_load)(void* handle) = nullptr;  // run once, before any function of it is called
  std::once_flag once{};
  std::atomic<void*> handle{nullptr};
};

// Loads the library once (dlopen of `variable`'s file, else its SONAME), looks up the index-th
// name, stores its address in the slot for the next calls and returns it. A library or a name
// that cannot be found is one error line and exit code 1, as every tw::Error: the first call can
// come from any thread and any frame (a destructor, a worker), where an exception could not be
// relied on to reach main. The exit skips destructors, so it first removes what the stagers
// registered (core/staging_registry.hpp): no temporary is left behind.
void* resolve_lazy(LazyLibrary& library, unsigned index);

}  // namespace tw

// Declares what the stubs of library `prefix` define (their tables) and call (the resolver, which
// the library's loader defines with resolve_lazy).
#define TW_LAZY_LIBRARY_TABLES(prefix)       \
  extern "C" {                               \
  extern void* prefix##_slots[];             \
  extern const char* const prefix##_names[]; \
  extern const std::size_t prefix##_count;   \
  extern const char prefix##_soname[];       \
  void* prefix##_resolve(unsigned index);    \
  }
