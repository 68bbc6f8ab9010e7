#pragma once
// Rendering a synthesis onto a window of the canvas: every canvas pixel (supersampled when the
// exemplar is finer than the canvas) -> the piece it lies in (lowest index on overlaps) ->
// exemplar coordinates through the placement's rigid transform (+ stitching) -> bilinear read.
// No distortion: each piece is an exact copy of an exemplar region (with `feather`, its
// channels blend into the neighbour's near the seams; its coverage never does).
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/exemplar.hpp"
#include "synth/synthesize.hpp"

namespace tw {

struct RenderedPattern {
  Window window;
  Raster<float> coverage;  // opaque fraction 0..1 (mean alpha)
  // One band per exemplar channel (same order as Exemplar::channel_names): alpha-weighted
  // means of the channel where covered, 0 elsewhere; the "A" band equals coverage.
  std::vector<Raster<float>> channels;
};

// `feather` > 0 (metres): within that distance of a seam between two non-empty pieces, every
// channel but alpha blends with the neighbouring piece's exemplar read on past its edge
// (half and half on the seam), so height and colour details meet instead of stepping. The
// coverage stays each piece's own, so avoidance is unchanged. 0: exact copies.
RenderedPattern render_pattern(const Exemplar& exemplar, const Ribbon& ribbon,
                               const Synthesis& synthesis, const GridSpec& canvas,
                               const Window& window, bool stitched = true, double feather = 0.0);

// The ribbon cage (piece outlines) over a window: 1 on the edges, 0 elsewhere; for pictures.
Raster<float> render_cage(const Ribbon& ribbon, const GridSpec& canvas, const Window& window);

// Opaque rendered pixels (coverage >= 0.5, i.e. a bilinear read of texels that are opaque for
// the DP) on forbidden pixels; a correct synthesis gives 0. `forbidden` covers the canvas.
std::int64_t count_avoidance_violations(const RenderedPattern& pattern,
                                        const SparseRaster<std::uint8_t>& forbidden);

}  // namespace tw
