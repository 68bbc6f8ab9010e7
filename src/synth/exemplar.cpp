#include "synth/exemplar.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "synth/detail/cost.hpp"

namespace tw {
namespace {

std::uint32_t to_byte(float v) {
  return std::uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

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

// Reads all channels of `path` as float (OIIO normalizes integer formats to 0..1).
std::vector<float> read_float_image(const std::string& path, OIIO::ImageSpec& spec,
                                    std::size_t budget, int extra_channels) {
  // Straight (unassociated) colours: ask readers not to premultiply (PNG, TIFF, ...).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input) fail("exemplar {}: cannot read ({})", path, oiio_errors(nullptr));
  spec = input->spec();
  const std::size_t bytes =
      std::size_t(spec.width) * spec.height * (spec.nchannels + extra_channels) * sizeof(float);
  if (bytes > budget)
    fail("exemplar {}: {}x{} with {} channels needs {} bytes, over the memory budget of {} bytes",
         path, spec.width, spec.height, spec.nchannels + extra_channels, bytes, budget);
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail("exemplar {}: cannot read pixels ({})", path, oiio_errors(input.get()));
  // Formats that store associated alpha (EXR) come back premultiplied: divide it out.
  if (spec.alpha_channel >= 0 && !spec.get_int_attribute("oiio:UnassociatedAlpha", 0)) {
    const int n = spec.nchannels, a = spec.alpha_channel;
    for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i) {
      float* t = pixels.data() + i * n;
      if (t[a] <= 0.0f) continue;
      for (int c = 0; c < std::min(n, 3); ++c)
        if (c != a) t[c] /= t[a];
    }
  }
  return pixels;
}

}  // namespace

int Exemplar::channel_index(const std::string& name) const {
  const auto it = std::find(channel_names.begin(), channel_names.end(), name);
  return it == channel_names.end() ? -1 : int(it - channel_names.begin());
}

Exemplar make_exemplar(int width, int height, std::vector<std::string> channel_names,
                       std::vector<float> texels, const std::string& label, bool continuous_alpha) {
  Exemplar e;
  e.width = width;
  e.height = height;
  e.channel_names = std::move(channel_names);
  e.texels = std::move(texels);
  e.path = label;
  const int n = e.channel_count();
  if (width <= 0 || height <= 0) fail("exemplar {}: empty image", label);
  if (e.texels.size() != std::size_t(width) * height * n)
    fail("exemplar {}: {} texel values for {}x{} with {} channels", label, e.texels.size(), width,
         height, n);
  const int a = e.channel_index("A");
  if (a < 0) fail("exemplar {}: no alpha channel (the alpha outlines the pattern)", label);
  int r = e.channel_index("R"), g = e.channel_index("G"), b = e.channel_index("B");
  if (r < 0 || g < 0 || b < 0) r = g = b = e.channel_index("Y");
  e.cost.width = width;
  e.cost.height = height;
  e.cost.binary_alpha = !continuous_alpha;
  e.cost.rgba.resize(std::size_t(width) * height);
  std::size_t opaque = 0, transparent = 0;
  for (std::size_t i = 0; i < e.cost.rgba.size(); ++i) {
    const float* t = e.texels.data() + i * n;
    const std::uint32_t alpha = to_byte(t[a]);
    auto premultiplied = [&](int c) { return c < 0 ? 0u : (to_byte(t[c]) * alpha + 127u) / 255u; };
    e.cost.rgba[i] = detail::pack_rgba(premultiplied(r), premultiplied(g), premultiplied(b), alpha);
    if (detail::is_opaque(e.cost.rgba[i])) ++opaque;
    if (alpha == 0) ++transparent;
  }
  if (opaque == 0) fail("exemplar {}: fully transparent (no opaque texel to synthesize)", label);
  if (transparent == 0)
    fail("exemplar {}: fully opaque (no transparent texel: pieces cannot slice the pattern)",
         label);
  return e;
}

Exemplar load_exemplar(const std::string& path, const ExemplarOptions& options) {
  OIIO::ImageSpec spec;
  const int extra = options.height_path.empty() ? 0 : 1;
  std::vector<float> pixels = read_float_image(path, spec, options.memory_budget_bytes, extra);
  std::vector<std::string> names = spec.channelnames;
  if (spec.alpha_channel >= 0 && spec.alpha_channel < int(names.size()))
    names[std::size_t(spec.alpha_channel)] = "A";
  for (auto& name : names)
    if (name == "Alpha" || name == "alpha" || name == "a") name = "A";
  if (std::find(names.begin(), names.end(), "A") == names.end())
    fail("exemplar {}: no alpha channel (the alpha outlines the pattern; channels: {})", path,
         fmt::join(spec.channelnames, ", "));
  if (extra) {
    OIIO::ImageSpec height_spec;
    const std::vector<float> heights =
        read_float_image(options.height_path, height_spec, options.memory_budget_bytes, 0);
    if (height_spec.width != spec.width || height_spec.height != spec.height)
      fail("exemplar height image {}: {}x{} but the exemplar {} is {}x{}", options.height_path,
           height_spec.width, height_spec.height, path, spec.width, spec.height);
    if (std::find(names.begin(), names.end(), "height") != names.end())
      fail("exemplar {}: already has a channel \"height\" and a height image {} was given", path,
           options.height_path);
    const int n = spec.nchannels, hn = height_spec.nchannels;
    std::vector<float> merged(std::size_t(spec.width) * spec.height * (n + 1));
    for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i) {
      std::copy_n(pixels.data() + i * n, n, merged.data() + i * (n + 1));
      merged[i * (n + 1) + n] = heights[i * hn];
    }
    pixels = std::move(merged);
    names.push_back("height");
  }
  return make_exemplar(spec.width, spec.height, std::move(names), std::move(pixels), path,
                       options.continuous_alpha);
}

}  // namespace tw
