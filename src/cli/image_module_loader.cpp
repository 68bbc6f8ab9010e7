// The `terraweave` program's definitions of image/image_io.hpp (issue #23 item 4): they load
// the `terraweave_image` module (image/image_io.cpp built with OpenImageIO) on the first image
// read or written and call it, so OpenImageIO and its ~150 shared libraries (ffmpeg, DCMTK,
// GStreamer, OpenCV ...) are loaded only by commands that touch an image. Linked before the
// libraries, these definitions keep libtw_synth's image_io.o (and with -Wl,--as-needed,
// OpenImageIO) out of the program; tests and programs built against the library call
// OpenImageIO directly. The module is looked for:
//   1. at TERRAWEAVE_IMAGE_MODULE (a file), when set;
//   2. beside the program (the build tree: build/src/);
//   3. in <program's folder>/../<libdir>/terraweave (an installed program: bin/terraweave).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "cli/image_module.hpp"
#include "core/error.hpp"
#include "core/resources.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

const ImageModule& image_module() {
  static const ImageModule* const table = [] {
    std::vector<fs::path> candidates;
    if (const char* set = std::getenv("TERRAWEAVE_IMAGE_MODULE"); set != nullptr && *set != '\0')
      candidates.emplace_back(set);
    const fs::path program = executable_path().parent_path();
    candidates.push_back(program / kImageModuleFile);
    candidates.push_back(
        (program.parent_path() / TERRAWEAVE_MODULE_DIR / kImageModuleFile).lexically_normal());
    std::string why;
    for (const fs::path& file : candidates) {
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) continue;
      void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        why = ::dlerror();
        continue;
      }
      using Entry = const ImageModule* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(handle, kImageModuleEntry));
      const ImageModule* found = entry ? entry() : nullptr;
      if (found != nullptr && found->version == kImageModuleVersion) return found;
      why = file.string() + " is not this terraweave's image module";
    }
    fail(
        "images need the module {} (OpenImageIO), not found beside the program or in {}{}; "
        "reinstall terraweave or set TERRAWEAVE_IMAGE_MODULE to its path",
        kImageModuleFile,
        (program.parent_path() / TERRAWEAVE_MODULE_DIR).lexically_normal().string(),
        why.empty() ? "" : " (" + why + ")");
  }();
  return *table;
}

}  // namespace

FloatImage read_float_image(const std::string& path, std::size_t budget_bytes, int extra_channels) {
  return image_module().read_float_image(path, budget_bytes, extra_channels);
}

ImageRows open_image_rows(const std::string& path) {
  return image_module().open_image_rows(path);
}

void read_image_rows(ImageRows& image, const std::string& path, int row, int rows,
                     std::vector<float>& out) {
  image_module().read_image_rows(image, path, row, rows, out);
}

void write_rgb8_image(const std::string& file, int width, int height, const std::uint8_t* rgb,
                      const std::string& shown) {
  image_module().write_rgb8_image(file, width, height, rgb, shown);
}

}  // namespace tw
