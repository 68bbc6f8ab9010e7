// cpp-httplib (`terraweave view --serve`) loaded on its first call (cli/lazy_library.hpp): it
// brings OpenSSL (libssl, libcrypto) and brotli, which no other command needs.
#ifdef TERRAWEAVE_LAZY_HTTPLIB

#include <cstddef>

#include "cli/lazy_library.hpp"

TW_LAZY_LIBRARY_TABLES(tw_httplib)

namespace tw {
namespace {

LazyLibrary httplib{.what = "cpp-httplib (view --serve)",
                    .variable = "TERRAWEAVE_HTTPLIB_LIBRARY",
                    .soname = tw_httplib_soname,
                    .slots = tw_httplib_slots,
                    .names = tw_httplib_names,
                    .count = tw_httplib_count};

}  // namespace
}  // namespace tw

extern "C" void* tw_httplib_resolve(unsigned index) {
  return tw::resolve_lazy(tw::httplib, index);
}

#endif
