#pragma once
// three.js (three.module.min.js, pinned by viewer/package-lock.json), embedded at build time
// (src/CMakeLists.txt, cmake/embed_file.cmake). Empty when npm was missing at build time.
#include <string_view>

namespace tw::detail {

extern const std::string_view kThreeJs;

}  // namespace tw::detail
