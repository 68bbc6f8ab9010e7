// Fuzz target: tw::load_sketch on an arbitrary file (read by OGR as GeoJSON). What it accepts
// passes check_sketch, the invariants the area synthesis relies on; what it refuses is a
// tw::Error naming the file and FID.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "sketch/sketch.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("terraweave-fuzz-sketch-" + std::to_string(::getpid()) + ".geojson");
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  tw::Sketch sketch;
  try {
    sketch = tw::load_sketch(path);
  } catch (const tw::Error&) {
    return 0;
  }
  try {
    tw::check_sketch(sketch);
  } catch (const tw::Error& e) {
    std::fprintf(stderr, "fuzz: %s\n", e.what());
    tw::fuzz::broken_promise("load_sketch accepted what check_sketch refuses");
  }
  return 0;
}
