// libFuzzer target: tw::parse_pipeline on arbitrary YAML text. A pipeline is either refused
// with a tw::Error or comes back holding only finite, positive lengths.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "pipeline/config.hpp"
#include "pipeline_invariants.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    tw::fuzz::check_pipeline(tw::parse_pipeline(text, "fuzz.yaml", "/fuzz"));
  } catch (const tw::Error&) {
    // Refused with a message: the expected answer to bad input.
  }
  return 0;
}
