// GDAL on first use (docs/performance.md, "GDAL on first use"): in a build with
// TERRAWEAVE_LAZY_GDAL the program calls GDAL through stubs (cmake/lazy_library_stubs.py) and
// libgdal, with its ~110 libraries, is loaded by the first GDAL call, so a command that calls
// none (render-tile of a generated world) never loads it.
#pragma once

#include <cpl_error.h>

namespace tw {

// GDAL's error handler: installed now, or in a lazy build as soon as GDAL is loaded (before
// the call that loads it runs), so setting it loads nothing.
void set_gdal_error_handler(CPLErrorHandler handler);

}  // namespace tw
