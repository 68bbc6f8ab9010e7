#include "terrain/ribbon_frame.hpp"

#include <cmath>

#include "terrain/detail/feature_index.hpp"

namespace tw {

RibbonFrame compute_ribbon_frame(const GridSpec& grid, const Window& window, const Curve& curve,
                                 double reach) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  RibbonFrame frame{window, Raster<float>(window.width, window.height, nan),
                    Raster<float>(window.width, window.height, nan)};
  const detail::FeatureIndex index(grid, window, {&curve}, {reach});
  std::vector<detail::NearestSample> samples;
  for (int t = 0; t < index.tile_count(); ++t) {
    const Window tile = index.tile(t);
    index.for_each_feature(t, samples, [&](int, const std::vector<detail::NearestSample>& s) {
      for (int r = 0; r < tile.height; ++r)
        for (int c = 0; c < tile.width; ++c) {
          const auto& n = s[std::size_t(r) * tile.width + c];
          if (!std::isfinite(n.distance)) continue;
          const int col = tile.col0 + c - window.col0, row = tile.row0 + r - window.row0;
          frame.along.at(col, row) = n.along;
          frame.across.at(col, row) = n.across;
        }
    });
  }
  return frame;
}

}  // namespace tw
