#include "terrain/splat.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "terrain/detail/feature_index.hpp"
#include "terrain/detail/influence.hpp"
#include "terrain/detail/precedence.hpp"

namespace tw {

const std::vector<std::string>& splat_materials() {
  static const std::vector<std::string> materials = {"base",     "road", "shoulder",
                                                     "riverbed", "bank", "ridge_rock"};
  return materials;
}

namespace {

enum Material { base, road, shoulder, riverbed, bank, ridge_rock, material_count };

// The inner and outer material of each kind (ridges have one: inner == outer).
constexpr std::array<std::array<int, 2>, 3> kKindMaterials = {
    {{road, shoulder}, {riverbed, bank}, {ridge_rock, ridge_rock}}};

// Per pixel and kind: the largest inner and outer coverage of the kind's features.
struct KindCoverage {
  float inner = 0.0f;
  float outer = 0.0f;
};

}  // namespace

namespace {

SplatLayers splat_over(const GridSpec& grid, const Window& window,
                       const std::vector<TerrainFeature>& features, const TerrainParams& params,
                       const Raster<float>* height) {
  const bool whole_grid = height && height->width == grid.width && height->height == grid.height;
  if (height && !whole_grid && (height->width != window.width || height->height != window.height))
    fail("compute_splat: height raster is {} x {}, neither the grid ({} x {}) nor the window",
         height->width, height->height, grid.width, grid.height);
  // Where pixel (0, 0) of `height` lies on the grid.
  const int height_col0 = whole_grid ? 0 : window.col0;
  const int height_row0 = whole_grid ? 0 : window.row0;
  const auto ranks = detail::precedence_ranks(params);
  std::vector<const Curve*> curves;
  std::vector<double> reach;
  const double pixel = std::min(grid.pixel_width, grid.pixel_height);
  for (const auto& f : features) {
    validate_feature(f);
    if (ranks[std::size_t(f.kind)] < 0)
      fail("{} feature FID {}: its kind is missing from the terrain precedence", to_string(f.kind),
           f.fid);
    curves.push_back(&f.centerline);
    // A bridge deck or tunnel paints nothing: the ground under it keeps its own materials.
    reach.push_back(f.structure == Structure::ground ? detail::splat_radii(f).outer + pixel
                                                      : -1.0);
  }
  SplatLayers out;
  out.materials = splat_materials();
  out.weights.resize(material_count);
  for (auto& w : out.weights) w = Raster<float>(window.width, window.height, 0.0f);

  const detail::FeatureIndex index(grid, window, curves, reach);
  const std::size_t kinds = params.precedence.size();
  tbb::parallel_for(tbb::blocked_range<int>(0, index.tile_count()), [&](const auto& range) {
    std::vector<detail::NearestSample> samples;
    std::vector<KindCoverage> cover;
    for (int t = range.begin(); t != range.end(); ++t) {
      const Window tile = index.tile(t);
      if (index.tile_is_empty(t)) {  // base only (filled here, in parallel, not up front)
        for (int r = tile.row0; r < tile.row_end(); ++r) {
          float* row = &out.weights[base].at(tile.col0 - window.col0, r - window.row0);
          std::fill(row, row + tile.width, 1.0f);
        }
        continue;
      }
      const std::size_t n = std::size_t(tile.width) * tile.height;
      cover.assign(n * kinds, KindCoverage{});
      index.for_each_feature(t, samples, [&](int fi, const std::vector<detail::NearestSample>& s) {
        const auto& f = features[std::size_t(fi)];
        const auto radii = detail::splat_radii(f);
        const std::size_t rank = std::size_t(ranks[std::size_t(f.kind)]);
        for (std::size_t k = 0; k < n; ++k) {
          if (!std::isfinite(s[k].distance)) continue;
          auto& c = cover[k * kinds + rank];
          c.inner = std::max(c.inner, float(detail::coverage(s[k].distance, radii.inner, pixel)));
          c.outer = std::max(c.outer, float(detail::coverage(s[k].distance, radii.outer, pixel)));
        }
      });
      for (int r = 0; r < tile.height; ++r)
        for (int c = 0; c < tile.width; ++c) {
          const std::size_t k = std::size_t(r) * tile.width + c;
          std::array<double, material_count> w{};
          w[base] = 1.0;
          if (height && std::isnan(height->at(tile.col0 - height_col0 + c, tile.row0 - height_row0 + r))) {
            out.weights[base].at(tile.col0 - window.col0 + c, tile.row0 - window.row0 + r) = 1.0f;
            continue;  // nothing is painted on nodata
          }
          // Each kind, in precedence order, covers what lies under it.
          for (std::size_t rank = 0; rank < kinds; ++rank) {
            const auto& cv = cover[k * kinds + rank];
            const double outer = std::max(cv.outer, cv.inner);
            if (outer <= 0.0) continue;
            for (double& m : w) m *= 1.0 - outer;
            const auto& mats = kKindMaterials[std::size_t(params.precedence[rank])];
            w[std::size_t(mats[0])] += cv.inner;
            w[std::size_t(mats[1])] += outer - cv.inner;
          }
          // Base takes exactly the rest, so the float weights sum to 1.
          float others = 0.0f;
          for (int m = base + 1; m < material_count; ++m) others += float(w[std::size_t(m)]);
          const float scale = others > 1.0f ? 1.0f / others : 1.0f;
          float sum = 0.0f;
          const int col = tile.col0 - window.col0 + c, row = tile.row0 - window.row0 + r;
          for (int m = base + 1; m < material_count; ++m) {
            const float v = float(w[std::size_t(m)]) * scale;
            out.weights[std::size_t(m)].at(col, row) = v;
            sum += v;
          }
          out.weights[base].at(col, row) = std::max(0.0f, 1.0f - sum);
        }
    }
  });
  return out;
}

}  // namespace

SplatLayers compute_splat(const GridSpec& grid, const Window& window,
                          const std::vector<TerrainFeature>& features,
                          const TerrainParams& params) {
  return splat_over(grid, window, features, params, nullptr);
}

SplatLayers compute_splat(const GridSpec& grid, const Window& window,
                          const std::vector<TerrainFeature>& features, const TerrainParams& params,
                          const Raster<float>& height) {
  return splat_over(grid, window, features, params, &height);
}

}  // namespace tw
