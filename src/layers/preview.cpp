// The preview: a look, not data. Hillshaded heights (box-downsampled to at most max_size
// pixels), tinted by elevation and by every splat material (patterns' too), with feature lines
// on top;
// 8-bit RGB through GDAL's PNG driver.
#include <cpl_string.h>
#include <gdal_priv.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "layers/detail/gdal_init.hpp"
#include "layers/detail/hillshade.hpp"
#include "layers/write.hpp"

namespace tw {

namespace {

using Rgb = std::array<float, 3>;

// Hypsometric tint from low (green) to high (pale tan); t outside [0, 1] or NaN is clamped.
Rgb elevation_tint(double t) {
  static constexpr std::array<Rgb, 4> stops = {
      {{96, 140, 80}, {150, 170, 100}, {190, 170, 120}, {225, 215, 200}}};
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0) * 3.0;
  const int i = std::min(2, int(t));
  const float f = float(t - i);
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = stops[i][k] + (stops[i + 1][k] - stops[i][k]) * f;
  return c;
}

// Every material but the base has a colour. Known ones keep theirs; any other (the materials a
// synthesized pattern adds, e.g. "splat.road_marking") gets one from preview_material_colour.
Rgb material_colour(const std::string& channel) {
  if (channel == "splat.base") return {-1, -1, -1};  // the elevation tint
  const Rgb8 c = preview_material_colour(channel);
  return {float(c[0]), float(c[1]), float(c[2])};
}

// Box average of a band over factor x factor blocks, ignoring NaN. Whole input rows are read
// in order (each output pixel still sums its block row by row, left to right).
Raster<float> downsample(const Raster<float>& band, int factor, int w, int h) {
  Raster<float> out(w, h, std::numeric_limits<float>::quiet_NaN());
  tbb::parallel_for(0, h, [&](int r) {
    std::vector<double> sum(std::size_t(w), 0.0);
    std::vector<int> count(std::size_t(w), 0);
    for (int y = r * factor; y < std::min(band.height, (r + 1) * factor); ++y) {
      const float* line = band.pixels.data() + std::size_t(y) * band.width;
      for (int c = 0; c < w; ++c) {
        const int x1 = std::min(band.width, (c + 1) * factor);
        for (int x = c * factor; x < x1; ++x) {
          const float v = line[x];
          if (!std::isnan(v)) sum[c] += v, ++count[c];
        }
      }
    }
    for (int c = 0; c < w; ++c)
      if (count[c] > 0) out.at(c, r) = float(sum[c] / count[c]);
  });
  return out;
}

}  // namespace

Rgb8 preview_material_colour(const std::string& channel) {
  if (channel == "splat.road") return {70, 70, 75};
  if (channel == "splat.shoulder") return {165, 150, 125};
  if (channel == "splat.riverbed") return {60, 125, 215};
  if (channel == "splat.bank") return {110, 125, 80};
  if (channel == "splat.ridge_rock") return {150, 140, 135};
  // The demo's pattern materials: markings read white on the dark road, the band rust-red on
  // the grey rock.
  if (channel == "splat.road_marking") return {250, 245, 215};
  if (channel == "splat.ridge_band") return {195, 85, 45};
  // Any other: a saturated hue from a hash of the name (FNV-1a, the same on every platform),
  // so a material keeps its colour from run to run.
  std::uint32_t hash = 2166136261u;
  for (const unsigned char ch : channel) hash = (hash ^ ch) * 16777619u;
  const double hue = double(hash % 360u) / 60.0;  // sextant of the colour wheel
  const double x = 1.0 - std::abs(std::fmod(hue, 2.0) - 1.0);
  std::array<double, 3> rgb{};
  switch (int(hue)) {
    case 0:
      rgb = {1, x, 0};
      break;
    case 1:
      rgb = {x, 1, 0};
      break;
    case 2:
      rgb = {0, 1, x};
      break;
    case 3:
      rgb = {0, x, 1};
      break;
    case 4:
      rgb = {x, 0, 1};
      break;
    default:
      rgb = {1, 0, x};
      break;
  }
  Rgb8 out;  // value 0.9, saturation 0.75: bright enough over the hillshade, never white
  for (int i = 0; i < 3; ++i)
    out[i] = std::uint8_t(std::lround(255.0 * 0.9 * (0.25 + 0.75 * rgb[i])));
  return out;
}

void write_preview_png(const LayerSet& set, const std::filesystem::path& path,
                       const std::vector<std::vector<Vec2>>& lines, int max_size) {
  const Layer* height = find_layer(set, "height");
  if (height == nullptr || height->bands.empty())
    fail("preview {}: the layer set has no 'height' layer", path.string());
  const GridSpec& g = set.grid;
  const int factor =
      std::max(1, int(std::ceil(double(std::max(g.width, g.height)) / std::max(1, max_size))));
  const int w = std::max(1, g.width / factor), h = std::max(1, g.height / factor);
  const Raster<float> z = downsample(height->bands[0], factor, w, h);

  // Non-finite heights draw as nodata. The range is in double: the difference of two finite
  // floats (even +-3e38) is finite there.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const float v : z.pixels)
    if (std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
  const double range = hi > lo ? hi - lo : 1.0;

  std::vector<std::pair<Rgb, Raster<float>>> materials;
  if (const Layer* splat = find_layer(set, "splat")) {
    for (std::size_t i = 0; i < splat->channels.size(); ++i) {
      const Rgb colour = material_colour(splat->channels[i]);
      if (colour[0] >= 0) materials.emplace_back(colour, downsample(splat->bands[i], factor, w, h));
    }
  }

  // Hillshade (sun from the north-west, 45 degrees up), slopes exaggerated 2x for legibility:
  // GDAL's (detail/hillshade.hpp).
  const Raster<float> light_of =
      detail::hillshade(z, g.pixel_width * factor, g.pixel_height * factor);
  std::array<std::vector<std::uint8_t>, 3> rgb;
  for (auto& channel : rgb) channel.assign(std::size_t(w) * h, 0);
  tbb::parallel_for(0, h, [&](int r) {
    for (int c = 0; c < w; ++c) {
      const std::size_t k = std::size_t(r) * w + c;
      const double v = z.at(c, r);
      if (!std::isfinite(v)) {  // nodata: a dark neutral grey
        for (auto& channel : rgb) channel[k] = 40;
        continue;
      }
      const double shade = light_of.at(c, r);
      // The weighted mean of the material colours, the base (and whatever weight is missing)
      // in the elevation tint: weights sum to 1, so a pattern's share shows as its share.
      const Rgb tint = elevation_tint((v - lo) / range);
      Rgb colour{0, 0, 0};
      float covered = 0.0f;
      for (const auto& [mc, weights] : materials) {
        const float m =
            std::isnan(weights.at(c, r)) ? 0.0f : std::clamp(weights.at(c, r), 0.0f, 1.0f);
        const float share = std::min(m, 1.0f - covered);
        covered += share;
        for (int i = 0; i < 3; ++i) colour[i] += mc[i] * share;
      }
      for (int i = 0; i < 3; ++i) colour[i] += tint[i] * (1.0f - covered);
      const double light = 0.35 + 0.75 * shade;
      for (int i = 0; i < 3; ++i)
        rgb[i][k] = std::uint8_t(std::clamp(colour[i] * light, 0.0, 255.0));
    }
  });

  // Feature lines: a thin pale stroke, sampled every half preview pixel (each pixel once).
  std::vector<char> drawn(std::size_t(w) * h, 0);
  for (const auto& line : lines)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec2 a = g.world_to_pixel(line[i]) / factor, b = g.world_to_pixel(line[i + 1]) / factor;
      const int steps = std::max(1, int(std::ceil(2.0 * distance(a, b))));
      for (int s = 0; s <= steps; ++s) {
        const Vec2 p = lerp(a, b, double(s) / steps);
        const int c = int(std::floor(p.x)), r = int(std::floor(p.y));
        if (c < 0 || r < 0 || c >= w || r >= h) continue;
        const std::size_t k = std::size_t(r) * w + c;
        if (drawn[k]) continue;
        drawn[k] = 1;
        // Half-transparent, so the road or river under the line stays visible.
        rgb[0][k] = std::uint8_t((rgb[0][k] + 255) / 2);
        rgb[1][k] = std::uint8_t((rgb[1][k] + 240) / 2);
        rgb[2][k] = std::uint8_t((rgb[2][k] + 120) / 2);
      }
    }

  detail::ensure_gdal_registered();
  CPLErrorReset();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
  if (mem == nullptr || png == nullptr)
    fail("GDAL lacks the MEM or PNG driver (writing {})", path.string());
  std::unique_ptr<GDALDataset> image(mem->Create("", w, h, 3, GDT_Byte, nullptr));
  for (int i = 0; i < 3; ++i)
    if (image->GetRasterBand(i + 1)->RasterIO(GF_Write, 0, 0, w, h, rgb[i].data(), w, h, GDT_Byte,
                                              0, 0) != CE_None)
      fail("preview {}: {}", path.string(), CPLGetLastErrorMsg());
  CPLStringList options;
  options.SetNameValue("ZLEVEL", "3");  // a preview: speed over the last bytes
  GDALDataset* out =
      png->CreateCopy(path.c_str(), image.get(), FALSE, options.List(), nullptr, nullptr);
  if (out == nullptr) fail("cannot write preview {}: {}", path.string(), CPLGetLastErrorMsg());
  GDALClose(out);
}

}  // namespace tw
