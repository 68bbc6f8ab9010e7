#include "synth/exemplar.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "image/image_io.hpp"
#include "synth/detail/cost.hpp"

namespace tw {
namespace {

std::uint32_t to_byte(float v) {
  return std::uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// Reads all channels of `path` as float (integer formats normalized to 0..1), straight colours.
FloatImage read_straight_image(const std::string& path, std::size_t budget, int extra_channels) {
  FloatImage image = read_float_image(path, budget, extra_channels);
  // Formats that store associated alpha (EXR) come back premultiplied: divide it out.
  if (image.alpha_channel >= 0 && !image.unassociated_alpha) {
    const int n = image.channels, a = image.alpha_channel;
    for (std::size_t i = 0; i < std::size_t(image.width) * image.height; ++i) {
      float* t = image.pixels.data() + i * n;
      if (t[a] <= 0.0f) continue;
      for (int c = 0; c < std::min(n, 3); ++c)
        if (c != a) t[c] /= t[a];
    }
  }
  return image;
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
  const int extra = options.height_path.empty() ? 0 : 1;
  FloatImage image = read_straight_image(path, options.memory_budget_bytes, extra);
  std::vector<std::string> names = image.channel_names;
  if (image.alpha_channel >= 0 && image.alpha_channel < int(names.size()))
    names[std::size_t(image.alpha_channel)] = "A";
  for (auto& name : names)
    if (name == "Alpha" || name == "alpha" || name == "a") name = "A";
  if (std::find(names.begin(), names.end(), "A") == names.end())
    fail("exemplar {}: no alpha channel (the alpha outlines the pattern; channels: {})", path,
         fmt::join(image.channel_names, ", "));
  std::vector<float> pixels = std::move(image.pixels);
  if (extra) {
    const FloatImage heights =
        read_straight_image(options.height_path, options.memory_budget_bytes, 0);
    if (heights.width != image.width || heights.height != image.height)
      fail("exemplar height image {}: {}x{} but the exemplar {} is {}x{}", options.height_path,
           heights.width, heights.height, path, image.width, image.height);
    if (std::find(names.begin(), names.end(), "height") != names.end())
      fail("exemplar {}: already has a channel \"height\" and a height image {} was given", path,
           options.height_path);
    const int n = image.channels, hn = heights.channels;
    std::vector<float> merged(std::size_t(image.width) * image.height * (n + 1));
    for (std::size_t i = 0; i < std::size_t(image.width) * image.height; ++i) {
      std::copy_n(pixels.data() + i * n, n, merged.data() + i * (n + 1));
      merged[i * (n + 1) + n] = heights.pixels[i * hn];
    }
    pixels = std::move(merged);
    names.push_back("height");
  }
  return make_exemplar(image.width, image.height, std::move(names), std::move(pixels), path,
                       options.continuous_alpha);
}

}  // namespace tw
