// The synthesizer's private fold-over mask (synth/detail/foldover.*, the renderer's winding
// test per pixel centre) against the raster module's (scanline pixel-centre rule, adjacent
// pieces exempt, bow-tie lobes): pixel for pixel on every built-in shape, widths that fold and
// widths that do not, off-lattice canvases and small sparse tiles. Equal masks let the raster
// module's be the only one.
#include <gtest/gtest.h>

#include <tuple>

#include "raster/foldover.hpp"
#include "synth/detail/foldover.hpp"
#include "synth/shapes.hpp"
#include "synth_fixtures.hpp"

namespace tw {
namespace {

struct Case {
  const char* shape;
  double length, width, delta, pixel;
  bool folds = false;  // the ribbon overdraws itself (so equality says something)
};

class FoldoverTwins : public ::testing::TestWithParam<Case> {};

TEST_P(FoldoverTwins, RasterMaskEqualsSynthMaskPixelForPixel) {
  const Case c = GetParam();
  const Ribbon ribbon = make_ribbon(make_shape(c.shape, c.length), {c.width, c.delta});
  GridSpec canvas = test::canvas_around(ribbon, c.pixel, 2.0 * c.pixel);
  canvas.origin_x += 0.37 * c.pixel;  // off the shape's lattice
  canvas.origin_y -= 0.21 * c.pixel;
  for (const int tile : {16, 0}) {
    const SparseRaster<std::uint8_t> synth = detail::foldover_mask(ribbon, canvas, tile);
    SparseRaster<std::uint8_t> raster(canvas.width, canvas.height, 0, tile);
    add_tiles(raster, ribbon_tiles(ribbon, canvas, tile, 2));
    add_foldovers(ribbon, canvas, raster);
    std::int64_t folded = 0, differ = 0;
    for (int row = 0; row < canvas.height; ++row)
      for (int col = 0; col < canvas.width; ++col) {
        folded += synth.at(col, row) != 0;
        differ += (synth.at(col, row) != 0) != (raster.at(col, row) != 0);
      }
    EXPECT_EQ(differ, 0) << c.shape << " width " << c.width << " tile " << tile << ": " << folded
                         << " folded";
    if (c.folds) {
      EXPECT_GT(folded, 20) << c.shape << " width " << c.width;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, FoldoverTwins,
    ::testing::Values(Case{"line", 60, 10, 3, 0.5}, Case{"arc", 60, 10, 3, 0.5},
                      Case{"s-curve", 60, 10, 3, 0.5}, Case{"circle", 60, 10, 3, 0.5},
                      Case{"heart", 60, 10, 3, 0.5}, Case{"hairpin", 60, 10, 3, 0.5, true},
                      Case{"hairpin", 60, 20, 2, 0.37, true}, Case{"arc", 20, 24, 2, 0.3, true},
                      Case{"s-curve", 30, 16, 1.5, 0.25}, Case{"heart", 40, 14, 2.5, 0.4},
                      Case{"circle", 20, 18, 2, 0.3}));

}  // namespace
}  // namespace tw
