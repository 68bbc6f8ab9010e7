#pragma once
// Spatial binning of feature segments into square pixel tiles, and the exact nearest-point
// frame of each feature over one tile. Shared by height operations, splat weights and
// compute_ribbon_frame: each tile only sees the segments whose reach touches it, so work is
// proportional to the pixels near features.
#include <cstdint>
#include <limits>
#include <vector>

#include "core/grid.hpp"
#include "ribbon/curve.hpp"

namespace tw::detail {

// The nearest centerline point of one feature seen from one pixel centre.
struct NearestSample {
  float distance = std::numeric_limits<float>::infinity();  // metres; inf beyond reach
  float along = 0.0f;                                       // arc length, metres
  float across = 0.0f;  // signed metres, > 0 on the left of the direction of travel
};

struct Segment {
  Vec2 a;
  Vec2 ab;          // b - a
  double s0 = 0.0;  // arc length at a
  double length = 0.0;
  double inv_length2 = 0.0;
  int feature = 0;
};

class FeatureIndex {
 public:
  // `reach[i]` is feature i's reach in metres. Tiles cover `window`, tile_size pixels square.
  FeatureIndex(const GridSpec& grid, const Window& window, const std::vector<const Curve*>& curves,
               const std::vector<double>& reach, int tile_size = 64);

  int tile_count() const { return tiles_x_ * tiles_y_; }
  Window tile(int t) const;
  bool tile_is_empty(int t) const { return offsets_[t] == offsets_[t + 1]; }

  // Calls visit(feature, samples) for each feature with a segment reaching tile t, in
  // feature order. `samples` holds tile.width * tile.height entries, row-major.
  template <class Visit>
  void for_each_feature(int t, std::vector<NearestSample>& samples, Visit&& visit) const {
    const Window w = tile(t);
    samples.resize(std::size_t(w.width) * w.height);
    std::int64_t k = offsets_[t];
    const std::int64_t end = offsets_[t + 1];
    while (k < end) {
      const int feature = segments_[bins_[k]].feature;
      std::fill(samples.begin(), samples.end(), NearestSample{});
      for (; k < end && segments_[bins_[k]].feature == feature; ++k)
        scan_segment(segments_[bins_[k]], w, samples);
      visit(feature, samples);
    }
  }

 private:
  void scan_segment(const Segment& s, const Window& w, std::vector<NearestSample>& samples) const;
  // Pixel rectangle [c0,c1) x [r0,r1) of the window whose centres may lie within reach of s.
  Window reach_pixels(const Segment& s) const;

  GridSpec grid_;
  Window window_;
  int tile_size_;
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  std::vector<double> reach_;
  std::vector<Segment> segments_;
  std::vector<std::int64_t> offsets_;  // CSR: tile t holds bins_[offsets_[t] .. offsets_[t+1])
  std::vector<int> bins_;              // segment ids, sorted by (feature, segment) per tile
};

}  // namespace tw::detail
