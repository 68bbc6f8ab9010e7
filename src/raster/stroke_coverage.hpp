#pragma once
// Anti-aliased coverage of stroked polylines (a shape-pattern's strokes: vine rows, posts,
// furrows) on a window of a grid, as a per-pixel function of the world grid: any window gives
// the same bits as the crop of the whole grid's result, so tiles are seamless.
#include <vector>

#include "core/grid.hpp"
#include "core/vec2.hpp"

namespace tw {

// Per pixel of `window`, in [0, 1]: the largest over the segments of every line of the overlap
// of the band [d - w/2, d + w/2] with the pixel's extent [-p/2, p/2], over p (d: distance from the
// pixel centre to the segment, w: the line's width, p: the mean pixel side). Exact for a band
// crossing a pixel along an axis; a stroke thinner than a pixel keeps its share w / p instead of
// vanishing or filling the pixel. Throws tw::Error unless there is one finite width >= 0 per line.
Raster<float> stroke_coverage(const std::vector<const std::vector<Vec2>*>& lines,
                              const std::vector<double>& widths, const GridSpec& grid,
                              const Window& window);

}  // namespace tw
