// Fuzz target: a run-cache entry (docs/cache.md) read from arbitrary bytes. read_cache_entry
// never throws: a bad file is State::corrupt with the reason, never trusted. What it reads as
// ok, written again, reads back as the same sections.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "pipeline/detail/cache_entry.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path folder =
      fs::temp_directory_path() / ("terraweave-fuzz-cache-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path input = folder / "in.twc", again = folder / "again.twc";
  {
    std::ofstream file(input, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  using State = tw::detail::CacheRead::State;
  const tw::detail::CacheRead read = tw::detail::read_cache_entry(input);
  if (read.state == State::absent) tw::fuzz::broken_promise("an existing file read as absent");
  if (read.state == State::corrupt && read.problem.empty())
    tw::fuzz::broken_promise("a corrupt entry without a reason");
  if (read.state != State::ok) return 0;
  tw::detail::write_cache_entry(again, read.sections);
  const tw::detail::CacheRead reread = tw::detail::read_cache_entry(again);
  if (reread.state != State::ok || reread.sections != read.sections)
    tw::fuzz::broken_promise("an entry changed through write and read");
  return 0;
}
