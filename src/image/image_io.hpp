#pragma once
// Every image file terraweave reads or writes through OpenImageIO, in one place (issue #23
// item 4): exemplars, the EXR bands `export` and `diff` read, RGB previews. The library's
// definitions (image_io.cpp) call OpenImageIO; the `terraweave` program defines the same
// functions instead by loading image_io.cpp, built as a module, on first use
// (src/cli/image_module_loader.cpp), so that a command that touches no image (render-tile,
// plan, a run without exemplars) does not load OpenImageIO's ~150 shared libraries.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tw {

struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;
  int alpha_channel = -1;           // -1: none
  bool unassociated_alpha = false;  // the colours are straight (not premultiplied) as stored
  std::vector<float> pixels;        // channels interleaved, row by row
};

// Every channel of `path` as float (integer formats normalized to 0..1; straight colours
// asked for). Throws tw::Error "exemplar PATH: ..." when it cannot be read or its pixels
// (plus `extra_channels` per pixel) need more than `budget_bytes`.
FloatImage read_float_image(const std::string& path, std::size_t budget_bytes, int extra_channels);

// An image opened to be read a few scanlines at a time.
struct ImageRows {
  int width = 0, height = 0;
  std::vector<std::string> channel_names;
  std::shared_ptr<void> input;  // the reader (closed with the last copy)
};
// Throws tw::Error "PATH: cannot be opened as an image: ..." .
ImageRows open_image_rows(const std::string& path);
// Rows [row, row + rows), channels interleaved, into `out` (resized). Throws tw::Error naming
// the file and the rows.
void read_image_rows(ImageRows& image, const std::string& path, int row, int rows,
                     std::vector<float>& out);

// An 8-bit RGB image (PNG by the file name's extension). Errors name `shown` (the final path
// when `file` is a staged one).
void write_rgb8_image(const std::string& file, int width, int height, const std::uint8_t* rgb,
                      const std::string& shown);

}  // namespace tw
