#pragma once
// Inputs shared by the OpenCL tests: the one OpenCL context of the test process, random and
// chain-like exemplars, footprints and column sets. Everything is drawn from a seeded
// std::mt19937 with integer distributions only, so a failing seed replays exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "synth/detail/stages.hpp"
#include "synth/opencl_context.hpp"

namespace tw::test {

// The context of the whole test process. Without a usable OpenCL platform the tests FAIL
// (CI installs PoCL): a skipped backend would hide a broken install.
inline OpenCLContext* opencl_context_or_null(std::string* why) {
  static std::string reason;
  static std::optional<OpenCLContext> context = OpenCLContext::create_default(&reason);
  *why = reason;
  return context ? &*context : nullptr;
}

#define TW_REQUIRE_OPENCL(context_variable)                                                \
  std::string opencl_why;                                                                  \
  ::tw::OpenCLContext* context_variable = ::tw::test::opencl_context_or_null(&opencl_why); \
  ASSERT_NE(context_variable, nullptr)                                                     \
      << "no usable OpenCL platform (install PoCL: apt-get install pocl-opencl-icd): "     \
      << opencl_why

inline std::uint32_t pack_rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

inline int uniform(std::mt19937& rng, int low, int high) {
  return std::uniform_int_distribution<int>(low, high)(rng);
}

// Random texels: `opaque_percent` of them opaque (alpha 128..255), the rest transparent
// (alpha 0..127) with arbitrary colours, so both alpha classes carry colour.
inline detail::CostTexels random_texels(std::mt19937& rng, int width, int height,
                                        int opaque_percent) {
  detail::CostTexels texels{width, height, {}, true};
  texels.rgba.resize(std::size_t(width) * height);
  for (std::uint32_t& t : texels.rgba) {
    const bool opaque = uniform(rng, 0, 99) < opaque_percent;
    t = pack_rgba(uniform(rng, 0, 255), uniform(rng, 0, 255), uniform(rng, 0, 255),
                  opaque ? uniform(rng, 128, 255) : uniform(rng, 0, 127));
  }
  return texels;
}

// A chain-like RGBA pattern: rows of elliptic links (opaque rings with smoothly varying
// colours) on a transparent background, like the paper's chain exemplars.
inline detail::CostTexels chain_texels(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  detail::CostTexels texels{width, height, {}, true};
  texels.rgba.assign(std::size_t(width) * height, 0);
  const int link = std::max(8, height / 3);
  const double cy = height / 2.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int index = x / link;
      const double cx = (index + 0.5) * link;
      const double ry = (index % 2 == 0 ? height * 0.3 : height * 0.18);
      const double rx = link * 0.62;
      const double e = std::hypot((x + 0.5 - cx) / rx, (y + 0.5 - cy) / ry);
      if (e > 0.7 && e < 1.0) {
        const int shade = int(80 + 120 * (1.0 - e) + uniform(rng, 0, 30));
        texels.rgba[std::size_t(y) * width + x] =
            pack_rgba(shade, shade - 20 + index % 3 * 10, 60 + index * 7 % 90, 255);
      }
    }
  }
  return texels;
}

// A plausible piece of C rows and `delta` columns with a tilted right edge (slope in 1/256
// texel per sample): top and bottom rows must be clear, the interior must hold something.
inline detail::PieceFootprint slanted_piece(int column, int delta, int slope) {
  detail::PieceFootprint piece;
  piece.column = column;
  for (int k = 0; k < column; ++k) {
    piece.right_fx.push_back(delta * 256 + 128 + (k - column / 2) * slope / 16);
    piece.right_fy.push_back(k * 256 + 128 + slope / 4);
  }
  for (int x = 0; x <= delta; ++x) {
    piece.must_be_clear.push_back({x, 0});
    piece.must_be_clear.push_back({x, column - 1});
  }
  for (int y = 1; y < column - 1; ++y)
    for (int x = 0; x <= delta; ++x) piece.interior.push_back({x, y});
  return piece;
}

// Random footprint offsets, reaching outside the exemplar on every side.
inline detail::PieceFootprint random_piece(std::mt19937& rng, int column) {
  detail::PieceFootprint piece;
  piece.column = column;
  for (int k = 0; k < column; ++k) {
    piece.right_fx.push_back(uniform(rng, -3 * 256, 12 * 256));
    piece.right_fy.push_back(uniform(rng, -2 * 256, (column + 2) * 256));
  }
  for (int i = uniform(rng, 0, 12); i > 0; --i)
    piece.must_be_clear.push_back({uniform(rng, -2, 8), uniform(rng, -2, column + 1)});
  for (int i = uniform(rng, 0, 40); i > 0; --i)
    piece.interior.push_back({uniform(rng, 0, 8), uniform(rng, 0, column - 1)});
  return piece;
}

}  // namespace tw::test
