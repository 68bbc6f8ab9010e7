#pragma once
// What every fuzz target shares: quiet logging, and the rule that a tw::Error is the expected
// answer to bad input (anything else that escapes, a crash or a sanitizer report is a finding).

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.hpp"
#include "core/log.hpp"

namespace tw::fuzz {

// Logging would cost more than the parsing; the fuzzers look at behaviour, not messages.
inline void silence_logging() {
  tw::set_log_level(spdlog::level::off);
}

// A finding that is not a crash: a value the code accepted although it breaks what the API
// promises. Aborting makes libFuzzer keep the input.
[[noreturn]] inline void broken_promise(const char* what) {
  std::fprintf(stderr, "fuzz: broken promise: %s\n", what);
  std::abort();
}

inline void expect_finite(double value, const char* what) {
  if (!std::isfinite(value)) broken_promise(what);
}

}  // namespace tw::fuzz
