// The entry point of the `terraweave_image` module: built with image/image_io.cpp and
// OpenImageIO, loaded by the program on its first image (cli/image_module_loader.cpp).
#include "cli/image_module.hpp"

extern "C" __attribute__((visibility("default"))) const tw::ImageModule* terraweave_image_module() {
  static const tw::ImageModule table{tw::kImageModuleVersion, &tw::read_float_image,
                                     &tw::open_image_rows, &tw::read_image_rows,
                                     &tw::write_rgb8_image};
  return &table;
}
