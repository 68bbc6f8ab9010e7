#include "raster/distance.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.hpp"

namespace tw {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One 1-D pass of Felzenszwalb & Huttenlocher: d[q] = min_p (w2 (q - p)^2 + f[p]) over the
// lower envelope of parabolas. Samples with f = +inf are not parabolas at all (skipping them
// avoids inf - inf in the intersection formula).
struct Envelope {
  std::vector<int> v;
  std::vector<double> z;
  void transform(const double* f, int n, double w2, double* d) {
    v.resize(std::size_t(n));
    z.resize(std::size_t(n) + 1);
    int k = -1;
    for (int q = 0; q < n; ++q) {
      if (f[q] == kInf) continue;
      const double fq = f[q] + w2 * double(q) * q;
      double s = -kInf;
      while (k >= 0) {
        const int p = v[k];
        s = (fq - (f[p] + w2 * double(p) * p)) / (2.0 * w2 * double(q - p));
        if (s > z[k]) break;
        --k;
      }
      ++k;
      v[k] = q;
      z[k] = k == 0 ? -kInf : s;
      z[k + 1] = kInf;
    }
    if (k < 0) {
      for (int q = 0; q < n; ++q) d[q] = kInf;
      return;
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
      while (z[j + 1] < q) ++j;
      const double dq = double(q - v[j]);
      d[q] = w2 * dq * dq + f[v[j]];
    }
  }
};

}  // namespace

Raster<float> distance_to_mask(const Raster<std::uint8_t>& mask, double pixel_w, double pixel_h) {
  if (!(pixel_w > 0.0) || !(pixel_h > 0.0))
    fail("distance_to_mask: pixel size must be > 0 (got {} x {})", pixel_w, pixel_h);
  const int w = mask.width, h = mask.height;
  Raster<float> out(w, h, 0.0f);
  if (w == 0 || h == 0) return out;
  // Squared distances along columns first (metres^2), then along rows. On a binary mask the
  // column pass is the squared distance to the nearest non-zero pixel of the column, found by
  // one scan down and one up (row-major, no division); it gives exactly the lower envelope's
  // values: the envelope's winner is the nearest pixel (ties are equally far), and both
  // evaluate w2 * dq * dq + 0.
  // Every cell is written by the column pass: no zero-fill (half a gigabyte at 8k^2).
  const auto columns = std::make_unique_for_overwrite<double[]>(std::size_t(w) * h);
  const double w2 = pixel_h * pixel_h;
  constexpr int kChunk = 256;
  tbb::parallel_for(tbb::blocked_range<int>(0, (w + kChunk - 1) / kChunk),
                    [&](const tbb::blocked_range<int>& range) {
                      std::vector<int> nearest(kChunk);
                      for (int chunk = range.begin(); chunk != range.end(); ++chunk) {
                        const int c0 = chunk * kChunk, n = std::min(w, c0 + kChunk) - c0;
                        std::fill(nearest.begin(), nearest.end(), -1);
                        for (int r = 0; r < h; ++r) {
                          const std::uint8_t* m = mask.pixels.data() + std::size_t(r) * w + c0;
                          double* d = columns.get() + std::size_t(r) * w + c0;
                          for (int i = 0; i < n; ++i) {
                            if (m[i]) nearest[i] = r;
                            const double dq = double(r - nearest[i]);
                            d[i] = nearest[i] < 0 ? kInf : w2 * dq * dq;
                          }
                        }
                        std::fill(nearest.begin(), nearest.end(), -1);
                        for (int r = h - 1; r >= 0; --r) {
                          const std::uint8_t* m = mask.pixels.data() + std::size_t(r) * w + c0;
                          double* d = columns.get() + std::size_t(r) * w + c0;
                          for (int i = 0; i < n; ++i) {
                            if (m[i]) nearest[i] = r;
                            const double dq = double(r - nearest[i]);
                            if (nearest[i] >= 0) d[i] = std::min(d[i], w2 * dq * dq);
                          }
                        }
                      }
                    });
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& range) {
    Envelope envelope;
    std::vector<double> d(static_cast<std::size_t>(w));
    for (int r = range.begin(); r != range.end(); ++r) {
      envelope.transform(columns.get() + std::size_t(r) * w, w, pixel_w * pixel_w, d.data());
      for (int c = 0; c < w; ++c) out.at(c, r) = float(std::sqrt(d[c]));
    }
  });
  return out;
}

}  // namespace tw
