#include "pipeline/detail/region.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw::detail {

Window region_window(const GridSpec& grid, const RegionConfig& region, const std::string& source) {
  const double west = grid.origin_x, north = grid.origin_y;
  const double east = west + grid.width * grid.pixel_width;
  const double south = north - grid.height * grid.pixel_height;
  if (region.min_x >= east || region.max_x <= west || region.min_y >= north ||
      region.max_y <= south) {
    fail("region [{}, {}, {}, {}]: does not overlap the heightfield {} ([{}, {}, {}, {}])",
         region.min_x, region.min_y, region.max_x, region.max_y, source, west, south, east, north);
  }
  // Cells that meet the open box: a region edge on a cell edge leaves that cell out.
  const auto first = [](double at) { return int(std::floor(at + 1e-9)); };
  const auto end = [](double at) { return int(std::ceil(at - 1e-9)); };
  const int col0 = std::max(0, first((region.min_x - west) / grid.pixel_width));
  const int col1 = std::min(grid.width, end((region.max_x - west) / grid.pixel_width));
  const int row0 = std::max(0, first((north - region.max_y) / grid.pixel_height));
  const int row1 = std::min(grid.height, end((north - region.min_y) / grid.pixel_height));
  return {col0, row0, std::max(1, col1 - col0), std::max(1, row1 - row0)};
}

}  // namespace tw::detail
