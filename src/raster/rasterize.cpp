#include "raster/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/enumerable_thread_specific.h>

#include "core/error.hpp"
#include "raster/detail/edge_builder.hpp"
#include "raster/detail/scanline.hpp"
#include "raster/detail/window_raster.hpp"

namespace tw {
namespace {

// Rows per parallel task: small enough to balance 2..64 threads on a tile, large enough that
// bucketing long edges stays cheap.
constexpr int kBlockRows = 16;

std::vector<detail::ScanEdge> polygon_edges(const std::vector<Polygon>& polygons,
                                            const GridSpec& grid, double scale,
                                            const Window& window) {
  detail::EdgeBuilder builder(grid, scale, window);
  for (std::size_t p = 0; p < polygons.size(); ++p)
    if (!builder.add_shape(polygons[p], std::uint32_t(p)))
      fail("polygon {}: a point is not finite", p);
  return std::move(builder.edges);
}

}  // namespace

void burn_polygons(const std::vector<Polygon>& polygons, const GridSpec& grid, const Window& window,
                   Raster<std::uint8_t>& out, std::uint8_t value) {
  detail::prepare_window_raster(out, window, "burn_polygons");
  const auto edges = polygon_edges(polygons, grid, 1.0, window);
  detail::scan_spans(edges, window.row0, window.row_end(), window.col0, window.col_end(),
                     kBlockRows, [&](int row, std::uint32_t, int c0, int c1) {
                       std::uint8_t* line =
                           out.pixels.data() + std::size_t(row - window.row0) * out.width;
                       std::memset(line + (c0 - window.col0), value, std::size_t(c1 - c0));
                     });
}

Raster<float> polygon_coverage(const std::vector<Polygon>& polygons, const GridSpec& grid,
                               const Window& window, int supersample) {
  detail::check_window(window, "polygon_coverage");
  if (supersample < 1 || supersample > 16)
    fail("polygon_coverage: supersample must be in 1..16 (got {})", supersample);
  const int s = supersample;
  const Window sub_window{window.col0 * s, window.row0 * s, window.width * s, window.height * s};
  const auto edges = polygon_edges(polygons, grid, double(s), sub_window);
  // Sub-pixel hits per pixel. Each sub-row's spans are merged first (their union), so
  // overlapping polygons are not counted twice; then whole pixels get s hits at once.
  Raster<std::uint16_t> hits(window.width, window.height, 0);
  // Blocks are whole pixel rows (multiples of s sub-rows), so a pixel row has a single writer.
  const int block = kBlockRows * s;
  struct Scratch {
    std::vector<std::pair<int, int>> spans;  // of the current sub-row
    std::vector<std::int32_t> whole;         // difference array of +s runs over the pixel row
  };
  tbb::enumerable_thread_specific<Scratch> scratch([&] {
    return Scratch{{}, std::vector<std::int32_t>(std::size_t(window.width) + 1, 0)};
  });
  detail::scan_spans(
      edges, sub_window.row0, sub_window.row_end(), sub_window.col0, sub_window.col_end(), block,
      [&](int, std::uint32_t, int c0, int c1) { scratch.local().spans.emplace_back(c0, c1); },
      [&](int sub_row) {
        // Named references, not a structured binding: clang before 16 cannot capture one in
        // the lambda below (the fuzz build uses Debian 12's clang 14).
        Scratch& local = scratch.local();
        auto& spans = local.spans;
        auto& whole = local.whole;
        std::uint16_t* out =
            hits.pixels.data() + std::size_t(sub_row / s - window.row0) * hits.width;
        // Sub-columns [a, b) relative to the window: partial pixels directly, whole ones in
        // the difference array.
        auto add = [&](int a, int b) {
          const int first_whole = (a + s - 1) / s, end_whole = b / s;
          if (first_whole > end_whole) {  // inside one pixel
            out[a / s] = std::uint16_t(out[a / s] + (b - a));
            return;
          }
          if (a < first_whole * s) out[a / s] = std::uint16_t(out[a / s] + (first_whole * s - a));
          if (end_whole * s < b)
            out[end_whole] = std::uint16_t(out[end_whole] + (b - end_whole * s));
          whole[std::size_t(first_whole)] += s;
          whole[std::size_t(end_whole)] -= s;
        };
        if (!spans.empty()) {
          std::sort(spans.begin(), spans.end());
          int run_begin = spans[0].first, run_end = spans[0].second;
          for (std::size_t i = 1; i < spans.size(); ++i) {
            if (spans[i].first > run_end) {
              add(run_begin - sub_window.col0, run_end - sub_window.col0);
              run_begin = spans[i].first;
            }
            run_end = std::max(run_end, spans[i].second);
          }
          add(run_begin - sub_window.col0, run_end - sub_window.col0);
          spans.clear();
        }
        if (sub_row % s == s - 1) {  // the pixel row is complete
          std::int32_t running = 0;
          for (int c = 0; c < window.width; ++c) {
            running += whole[std::size_t(c)];
            out[c] = std::uint16_t(out[c] + running);
          }
          std::fill(whole.begin(), whole.end(), 0);
        }
      });
  Raster<float> coverage(window.width, window.height, 0.0f);
  const float scale = 1.0f / float(s * s);
  for (std::size_t i = 0; i < hits.pixels.size(); ++i) coverage.pixels[i] = hits.pixels[i] * scale;
  return coverage;
}

void burn_buffered_lines(const std::vector<std::vector<Vec2>>& lines,
                         const std::vector<double>& widths_m, const GridSpec& grid,
                         const Window& window, Raster<std::uint8_t>& out, std::uint8_t value) {
  detail::prepare_window_raster(out, window, "burn_buffered_lines");
  if (lines.size() != widths_m.size())
    fail("burn_buffered_lines: {} lines but {} widths", lines.size(), widths_m.size());
  struct Segment {
    Vec2 a, b;
    double radius;
  };
  std::vector<Segment> segments;
  // Each segment's capsule becomes a pseudo-edge whose row range is what the scanline bucketing
  // needs; the interval on a row is computed exactly below.
  std::vector<detail::ScanEdge> spans;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const double r = widths_m[l] / 2.0;
    if (!std::isfinite(r) || r < 0.0) fail("line {}: width {} m is not >= 0", l, widths_m[l]);
    const auto& line = lines[l];
    for (std::size_t i = 0; i < line.size(); ++i)
      if (!is_finite(line[i])) fail("line {}: point {} is not finite", l, i);
    // A single point buffers to a disc: a zero-length segment.
    const std::size_t segment_count = line.size() == 1 ? 1 : (line.empty() ? 0 : line.size() - 1);
    for (std::size_t i = 0; i < segment_count; ++i) {
      const Vec2 a = line[i];
      const Vec2 b = line[std::min(i + 1, line.size() - 1)];
      const double top = std::max(a.y, b.y) + r, bottom = std::min(a.y, b.y) - r;
      detail::ScanEdge e;
      // Rows whose centre world y lies in [bottom, top].
      e.row_begin = int(std::ceil((grid.origin_y - top) / grid.pixel_height - 0.5));
      e.row_end = int(std::floor((grid.origin_y - bottom) / grid.pixel_height - 0.5)) + 1;
      e.shape = std::uint32_t(segments.size());
      segments.push_back({a, b, r});
      if (e.row_begin < e.row_end) spans.push_back(e);
    }
  }
  if (spans.empty() || window.width == 0 || window.height == 0) return;
  const auto buckets = detail::bucket_edges(spans, window.row0, window.row_end(), kBlockRows);
  const int blocks = int(buckets.offsets.size()) - 1;
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& range) {
    for (int b = range.begin(); b != range.end(); ++b) {
      const int r0 = window.row0 + b * kBlockRows;
      const int r1 = std::min(window.row_end(), r0 + kBlockRows);
      for (std::uint32_t k = buckets.offsets[b]; k < buckets.offsets[b + 1]; ++k) {
        const detail::ScanEdge& e = spans[buckets.edge_ids[k]];
        const Segment& seg = segments[e.shape];
        for (int row = std::max(r0, e.row_begin); row < std::min(r1, e.row_end); ++row) {
          const double y = grid.origin_y - (row + 0.5) * grid.pixel_height;
          double lo = INFINITY, hi = -INFINITY;
          auto disc = [&](Vec2 c) {
            const double dy = y - c.y, h2 = seg.radius * seg.radius - dy * dy;
            if (h2 < 0.0) return;
            const double h = std::sqrt(h2);
            lo = std::min(lo, c.x - h);
            hi = std::max(hi, c.x + h);
          };
          disc(seg.a);
          disc(seg.b);
          const Vec2 n = perp(normalized(seg.b - seg.a)) * seg.radius;
          if (seg.a != seg.b) {
            const Vec2 quad[4] = {seg.a + n, seg.b + n, seg.b - n, seg.a - n};
            for (int q = 0; q < 4; ++q) {
              const Vec2 p = quad[q], s = quad[(q + 1) % 4];
              if ((p.y - y) * (s.y - y) > 0.0) continue;
              if (p.y == s.y) {
                lo = std::min({lo, p.x, s.x});
                hi = std::max({hi, p.x, s.x});
              } else {
                const double x = p.x + (y - p.y) * (s.x - p.x) / (s.y - p.y);
                lo = std::min(lo, x);
                hi = std::max(hi, x);
              }
            }
          }
          if (!(lo <= hi)) continue;
          const double c_lo = std::ceil((lo - grid.origin_x) / grid.pixel_width - 0.5);
          const double c_hi = std::floor((hi - grid.origin_x) / grid.pixel_width - 0.5) + 1.0;
          const int c0 = int(std::clamp(c_lo, double(window.col0), double(window.col_end())));
          const int c1 = int(std::clamp(c_hi, double(window.col0), double(window.col_end())));
          if (c0 >= c1) continue;
          std::uint8_t* line = out.pixels.data() + std::size_t(row - window.row0) * out.width;
          std::memset(line + (c0 - window.col0), value, std::size_t(c1 - c0));
        }
      }
    }
  });
}

}  // namespace tw
