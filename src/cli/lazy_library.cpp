#include "cli/lazy_library.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "core/staging_registry.hpp"

namespace tw {
namespace {

[[noreturn]] void give_up(const LazyLibrary& library, const char* what, const char* name,
                          const char* why) {
  std::fflush(stdout);
  std::fprintf(stderr,
               "terraweave: error: %s is needed here but %s %s (%s); install it or set %s to "
               "its library's path\n",
               library.what, what, name, why != nullptr ? why : "unknown reason", library.variable);
  std::fflush(stderr);
  // _exit skips the stagers' destructors: what they were writing goes here instead.
  remove_registered_staging();
  _exit(1);
}

}  // namespace

void* resolve_lazy(LazyLibrary& library, unsigned index) {
  std::call_once(library.once, [&] {
    const char* set = std::getenv(library.variable);
    const char* file = set != nullptr && *set != '\0' ? set : library.soname;
    void* handle = ::dlopen(file, RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) give_up(library, "could not load", file, ::dlerror());
    if (library.on_load != nullptr) library.on_load(handle);
    library.handle.store(handle);
  });
  const char* name = index < library.count ? library.names[index] : "(unknown symbol)";
  void* address = ::dlsym(library.handle.load(), name);
  if (address == nullptr) give_up(library, "has no function", name, ::dlerror());
  __atomic_store_n(&library.slots[index], address, __ATOMIC_RELEASE);
  return address;
}

}  // namespace tw
