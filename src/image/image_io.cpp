// OpenImageIO's side of image/image_io.hpp. Compiled into tw_synth, and on its own into the
// `terraweave_image` module that the program loads on first use (src/CMakeLists.txt): keep
// every OpenImageIO call of terraweave here, and nothing else.
#include "image/image_io.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "core/error.hpp"

namespace tw {
namespace {

// Every error OIIO holds for this read, taken (so none is left pending) and joined on one line:
// the reader's own and the global one.
std::string oiio_errors(const OIIO::ImageInput* input) {
  std::string text = input ? input->geterror() : std::string();
  const std::string global = OIIO::geterror();
  if (!global.empty()) text += (text.empty() ? "" : "\n") + global;
  std::string joined;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end > start) joined += (joined.empty() ? "" : "; ") + text.substr(start, end - start);
    start = end + 1;
  }
  return joined.empty() ? "unknown error" : joined;
}

}  // namespace

FloatImage read_float_image(const std::string& path, std::size_t budget_bytes, int extra_channels) {
  // Straight (unassociated) colours: ask readers not to premultiply (PNG, TIFF, ...).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input) fail("exemplar {}: cannot read ({})", path, oiio_errors(nullptr));
  const OIIO::ImageSpec& spec = input->spec();
  const std::size_t bytes =
      std::size_t(spec.width) * spec.height * (spec.nchannels + extra_channels) * sizeof(float);
  if (bytes > budget_bytes)
    fail("exemplar {}: {}x{} with {} channels needs {} bytes, over the memory budget of {} bytes",
         path, spec.width, spec.height, spec.nchannels + extra_channels, bytes, budget_bytes);
  FloatImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.channel_names = spec.channelnames;
  image.alpha_channel = spec.alpha_channel;
  image.unassociated_alpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  image.pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    fail("exemplar {}: cannot read pixels ({})", path, oiio_errors(input.get()));
  return image;
}

ImageRows open_image_rows(const std::string& path) {
  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
  if (!input) fail("{}: cannot be opened as an image: {}", path, OIIO::geterror());
  ImageRows image;
  image.width = input->spec().width;
  image.height = input->spec().height;
  image.channel_names = input->spec().channelnames;
  image.input = std::shared_ptr<OIIO::ImageInput>(std::move(input));
  return image;
}

void read_image_rows(ImageRows& image, const std::string& path, int row, int rows,
                     std::vector<float>& out) {
  auto* input = static_cast<OIIO::ImageInput*>(image.input.get());
  const int n = int(image.channel_names.size());
  out.resize(std::size_t(n) * rows * image.width);
  if (!input->read_scanlines(0, 0, row, row + rows, 0, 0, n, OIIO::TypeFloat, out.data()))
    fail("{}: cannot read rows {}..{}: {}", path, row, row + rows, input->geterror());
}

void write_rgb8_image(const std::string& file, int width, int height, const std::uint8_t* rgb,
                      const std::string& shown) {
  auto out = OIIO::ImageOutput::create(file);
  if (!out) fail("{}: cannot write: {}", shown, OIIO::geterror());
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(file, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb) || !out->close())
    fail("{}: cannot write: {}", shown, out->geterror());
}

}  // namespace tw
