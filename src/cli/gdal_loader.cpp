// The resolver of the GDAL stubs (cli/gdal_loader.hpp). The generated assembly
// (build/generated/gdal_stubs.S) defines one function per GDAL symbol the program calls, each
// jumping through a slot; a slot first leads to tw_gdal_resolve(index), which loads libgdal
// once (by its SONAME, or TERRAWEAVE_GDAL_LIBRARY), looks the name up, stores the address in
// the slot for the next calls and returns it to the stub, which jumps there with the caller's
// arguments. A missing library is one error line and exit code 1, as every tw::Error: the
// first call can come from any thread and any frame (a destructor, a worker), where an
// exception could not be relied on to reach main.
#include "cli/gdal_loader.hpp"

#ifdef TERRAWEAVE_LAZY_GDAL

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <mutex>

extern "C" {
extern void* tw_gdal_slots[];
extern const char* const tw_gdal_names[];
extern const std::size_t tw_gdal_count;
extern const char tw_gdal_soname[];
void* tw_gdal_resolve(unsigned index);
}

namespace tw {
namespace {

std::atomic<CPLErrorHandler> pending_handler{nullptr};
std::atomic<void*> library{nullptr};

[[noreturn]] void give_up(const char* what, const char* name, const char* why) {
  std::fflush(stdout);
  std::fprintf(stderr,
               "terraweave: error: GDAL is needed here but %s %s (%s); install GDAL "
               "(Debian: libgdal32) or set TERRAWEAVE_GDAL_LIBRARY to libgdal's path\n",
               what, name, why != nullptr ? why : "unknown reason");
  std::fflush(stderr);
  _exit(1);
}

void* load_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    const char* set = std::getenv("TERRAWEAVE_GDAL_LIBRARY");
    const char* file = set != nullptr && *set != '\0' ? set : tw_gdal_soname;
    void* handle = ::dlopen(file, RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) give_up("could not load", file, ::dlerror());
    if (const CPLErrorHandler handler = pending_handler.load()) {
      using SetHandler = CPLErrorHandler (*)(CPLErrorHandler);
      if (auto set_handler = reinterpret_cast<SetHandler>(::dlsym(handle, "CPLSetErrorHandler")))
        set_handler(handler);
    }
    library.store(handle);
  });
  return library.load();
}

}  // namespace

void set_gdal_error_handler(CPLErrorHandler handler) {
  pending_handler.store(handler);
  if (void* handle = library.load()) {
    using SetHandler = CPLErrorHandler (*)(CPLErrorHandler);
    if (auto set_handler = reinterpret_cast<SetHandler>(::dlsym(handle, "CPLSetErrorHandler")))
      set_handler(handler);
  }
}

}  // namespace tw

extern "C" void* tw_gdal_resolve(unsigned index) {
  void* handle = tw::load_gdal();
  const char* name = index < tw_gdal_count ? tw_gdal_names[index] : "(unknown symbol)";
  void* address = ::dlsym(handle, name);
  if (address == nullptr) tw::give_up("its function", name, ::dlerror());
  __atomic_store_n(&tw_gdal_slots[index], address, __ATOMIC_RELEASE);
  return address;
}

#else  // GDAL linked as usual

namespace tw {

void set_gdal_error_handler(CPLErrorHandler handler) {
  CPLSetErrorHandler(handler);
}

}  // namespace tw

#endif
