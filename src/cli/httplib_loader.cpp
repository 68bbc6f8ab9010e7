// cpp-httplib (`terraweave view --serve`) loaded on its first call (cli/lazy_library.hpp): it
// brings OpenSSL (libssl, libcrypto) and brotli, which no other command needs.
#ifdef TERRAWEAVE_LAZY_HTTPLIB

#include <cstddef>

#include "cli/lazy_library.hpp"

extern "C" {
extern void* tw_httplib_slots[];
extern const char* const tw_httplib_names[];
extern const std::size_t tw_httplib_count;
extern const char tw_httplib_soname[];
void* tw_httplib_resolve(unsigned index);
}

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
