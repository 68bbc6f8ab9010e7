#pragma once
// The table the `terraweave_image` module (image/image_io.cpp with OpenImageIO) hands the
// program (cli/image_module_loader.cpp): image/image_io.hpp's functions, by pointer.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image_io.hpp"

namespace tw {

struct ImageModule {
  int version = 1;  // kImageModuleVersion of the module's build
  FloatImage (*read_float_image)(const std::string&, std::size_t, int) = nullptr;
  ImageRows (*open_image_rows)(const std::string&) = nullptr;
  void (*read_image_rows)(ImageRows&, const std::string&, int, int, std::vector<float>&) = nullptr;
  void (*write_rgb8_image)(const std::string&, int, int, const std::uint8_t*,
                           const std::string&) = nullptr;
};

inline constexpr int kImageModuleVersion = 1;
inline constexpr const char* kImageModuleFile = "libterraweave_image.so";
inline constexpr const char* kImageModuleEntry = "terraweave_image_module";

}  // namespace tw
