#include "terrain/detail/feature_index.hpp"

#include <algorithm>
#include <cmath>

namespace tw::detail {

FeatureIndex::FeatureIndex(const GridSpec& grid, const Window& window,
                           const std::vector<const Curve*>& curves,
                           const std::vector<double>& reach, int tile_size)
    : grid_(grid), window_(window), tile_size_(tile_size), reach_(reach) {
  tiles_x_ = (window.width + tile_size - 1) / tile_size;
  tiles_y_ = (window.height + tile_size - 1) / tile_size;
  for (std::size_t f = 0; f < curves.size(); ++f) {
    const auto& p = curves[f]->points;
    const std::size_t n = p.size();
    const std::size_t count = curves[f]->closed ? n : (n > 0 ? n - 1 : 0);
    double s = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      Segment seg;
      seg.a = p[i];
      seg.ab = p[(i + 1) % n] - p[i];
      seg.s0 = s;
      seg.length = length(seg.ab);
      seg.inv_length2 = seg.length > 0.0 ? 1.0 / (seg.length * seg.length) : 0.0;
      seg.feature = int(f);
      s += seg.length;
      segments_.push_back(seg);
    }
  }
  // Two passes (count, fill) over segments in (feature, segment) order keep every tile's
  // list sorted without a sort.
  std::vector<std::int64_t> counts(std::size_t(tile_count()) + 1, 0);
  auto for_tiles = [&](const Segment& s, auto&& fn) {
    const Window r = reach_pixels(s);
    if (r.width <= 0 || r.height <= 0) return;
    const int tx0 = (r.col0 - window_.col0) / tile_size_;
    const int tx1 = (r.col_end() - 1 - window_.col0) / tile_size_;
    const int ty0 = (r.row0 - window_.row0) / tile_size_;
    const int ty1 = (r.row_end() - 1 - window_.row0) / tile_size_;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) fn(ty * tiles_x_ + tx);
  };
  for (const auto& s : segments_) for_tiles(s, [&](int t) { ++counts[t + 1]; });
  for (std::size_t t = 1; t < counts.size(); ++t) counts[t] += counts[t - 1];
  offsets_ = counts;
  bins_.resize(std::size_t(offsets_.back()));
  for (std::size_t i = 0; i < segments_.size(); ++i)
    for_tiles(segments_[i], [&](int t) { bins_[counts[t]++] = int(i); });
}

Window FeatureIndex::tile(int t) const {
  const int tx = t % tiles_x_, ty = t / tiles_x_;
  const int c0 = window_.col0 + tx * tile_size_, r0 = window_.row0 + ty * tile_size_;
  return {c0, r0, std::min(tile_size_, window_.col_end() - c0),
          std::min(tile_size_, window_.row_end() - r0)};
}

Window FeatureIndex::reach_pixels(const Segment& s) const {
  const double r = reach_[s.feature];
  const Vec2 b = s.a + s.ab;
  const Vec2 p0 = grid_.world_to_pixel({std::min(s.a.x, b.x) - r, std::max(s.a.y, b.y) + r});
  const Vec2 p1 = grid_.world_to_pixel({std::max(s.a.x, b.x) + r, std::min(s.a.y, b.y) - r});
  // Pixel centres at col + 0.5 inside [p0.x, p1.x].
  const double lo_c = std::ceil(p0.x - 0.5), hi_c = std::floor(p1.x - 0.5);
  const double lo_r = std::ceil(p0.y - 0.5), hi_r = std::floor(p1.y - 0.5);
  const int c0 = int(std::clamp(lo_c, double(window_.col0), double(window_.col_end())));
  const int c1 = int(std::clamp(hi_c + 1.0, double(window_.col0), double(window_.col_end())));
  const int r0 = int(std::clamp(lo_r, double(window_.row0), double(window_.row_end())));
  const int r1 = int(std::clamp(hi_r + 1.0, double(window_.row0), double(window_.row_end())));
  return {c0, r0, c1 - c0, r1 - r0};
}

void FeatureIndex::scan_segment(const Segment& s, const Window& w,
                                std::vector<NearestSample>& samples) const {
  const Window r = reach_pixels(s);
  const int c0 = std::max(r.col0, w.col0), c1 = std::min(r.col_end(), w.col_end());
  const int r0 = std::max(r.row0, w.row0), r1 = std::min(r.row_end(), w.row_end());
  const double reach = reach_[s.feature];
  for (int row = r0; row < r1; ++row) {
    const double y = grid_.origin_y - (row + 0.5) * grid_.pixel_height;
    NearestSample* line = samples.data() + std::size_t(row - w.row0) * w.width - w.col0;
    for (int col = c0; col < c1; ++col) {
      const Vec2 p{grid_.origin_x + (col + 0.5) * grid_.pixel_width, y};
      const Vec2 ap = p - s.a;
      const double t = std::clamp(dot(ap, s.ab) * s.inv_length2, 0.0, 1.0);
      const Vec2 q = ap - s.ab * t;
      const double d = std::sqrt(dot(q, q));
      // Strictly nearer only: ties keep the earlier segment, whatever the tile layout.
      if (d <= reach && float(d) < line[col].distance) {
        line[col].distance = float(d);
        line[col].along = float(s.s0 + t * s.length);
        line[col].across = float(cross(s.ab, ap) >= 0.0 ? d : -d);
      }
    }
  }
}

}  // namespace tw::detail
