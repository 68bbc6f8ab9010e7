#pragma once
// One exception type for everything a user can get wrong (files, keys, features, pieces).
// The message names the culprit; the CLI prints it as one line and exits non-zero.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace tw {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <class... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace tw
