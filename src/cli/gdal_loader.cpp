// GDAL's side of the program's lazy libraries (cli/lazy_library.hpp): the resolver its stubs
// call, and GDAL's error handler installed as libgdal loads.
#include "cli/gdal_loader.hpp"

#ifdef TERRAWEAVE_LAZY_GDAL

#include <dlfcn.h>

#include <atomic>
#include <cstddef>

#include "cli/lazy_library.hpp"

TW_LAZY_LIBRARY_TABLES(tw_gdal)

namespace tw {
namespace {

std::atomic<CPLErrorHandler> pending_handler{nullptr};

void install_handler(void* handle) {
  using SetHandler = CPLErrorHandler (*)(CPLErrorHandler);
  const CPLErrorHandler handler = pending_handler.load();
  auto set_handler = reinterpret_cast<SetHandler>(::dlsym(handle, "CPLSetErrorHandler"));
  if (handler != nullptr && set_handler != nullptr) set_handler(handler);
}

LazyLibrary gdal{.what = "GDAL",
                 .variable = "TERRAWEAVE_GDAL_LIBRARY",
                 .soname = tw_gdal_soname,
                 .slots = tw_gdal_slots,
                 .names = tw_gdal_names,
                 .count = tw_gdal_count,
                 .on_load = install_handler};

}  // namespace

void set_gdal_error_handler(CPLErrorHandler handler) {
  pending_handler.store(handler);
  if (void* handle = gdal.handle.load()) install_handler(handle);
}

}  // namespace tw

extern "C" void* tw_gdal_resolve(unsigned index) {
  return tw::resolve_lazy(tw::gdal, index);
}

#else  // GDAL linked as usual

namespace tw {

void set_gdal_error_handler(CPLErrorHandler handler) {
  CPLSetErrorHandler(handler);
}

}  // namespace tw

#endif
