#include "pipeline/detail/region.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "geo/resample.hpp"

namespace tw::detail {

Heightfield crop_to_region(const Heightfield& source, const RegionConfig& region, double resolution,
                           Resampling resampling) {
  const GridSpec& from = source.grid;
  const double west = from.origin_x, north = from.origin_y;
  const double east = west + from.width * from.pixel_width;
  const double south = north - from.height * from.pixel_height;
  const double min_x = std::max(region.min_x, west), max_x = std::min(region.max_x, east);
  const double min_y = std::max(region.min_y, south), max_y = std::min(region.max_y, north);
  if (min_x >= max_x || min_y >= max_y) {
    fail("region [{}, {}, {}, {}]: does not overlap the heightfield {} ([{}, {}, {}, {}])",
         region.min_x, region.min_y, region.max_x, region.max_y, source.source, west, south, east,
         north);
  }
  Heightfield out;
  out.crs_wkt = source.crs_wkt;
  out.nodata_value = source.nodata_value;
  out.source = source.source;
  GridSpec& g = out.grid;
  g.pixel_width = g.pixel_height = resolution;
  g.origin_x = std::floor(min_x / resolution) * resolution;
  g.origin_y = std::ceil(max_y / resolution) * resolution;
  g.width = std::max(1, int(std::ceil((max_x - g.origin_x) / resolution - 1e-9)));
  g.height = std::max(1, int(std::ceil((g.origin_y - min_y) / resolution - 1e-9)));
  out.height = resample_heights(source.height, from, g, resampling);
  return out;
}

}  // namespace tw::detail
