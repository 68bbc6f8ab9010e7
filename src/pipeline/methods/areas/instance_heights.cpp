#include "pipeline/methods/areas/instance_heights.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace tw::detail {

std::string instance_heights_fact(const GridSpec& grid, const AreasPlan& areas,
                                  const Raster<float>& height, const Window& halo,
                                  const Window& core) {
  std::string fact;
  for (std::size_t a = 0; a < areas.areas.size(); ++a) {
    const std::vector<ShapeInstance>& instances = areas.areas[a].pattern.instances;
    for (std::size_t i = 0; i < instances.size(); ++i) {
      const Vec2 p = grid.world_to_pixel(instances[i].position);
      const double col = std::floor(p.x), row = std::floor(p.y);
      if (!(col >= core.col0 && col < core.col_end() && row >= core.row0 && row < core.row_end()))
        continue;
      const float z = height.at(int(col) - halo.col0, int(row) - halo.row0);
      // The float's bits: exact, NaN (nodata) included.
      fact += fmt::format("{} {} {}\n", a, i, std::bit_cast<std::uint32_t>(z));
    }
  }
  return fact;
}

InstanceHeights unknown_instance_heights(const AreasPlan& areas) {
  InstanceHeights heights;
  for (const PlannedArea& area : areas.areas)
    heights.emplace_back(area.pattern.instances.size(), std::numeric_limits<double>::quiet_NaN());
  return heights;
}

void add_instance_heights(const std::string& fact, const std::string& where,
                          InstanceHeights& heights) {
  std::istringstream in(fact);
  std::size_t area = 0, instance = 0;
  std::uint32_t bits = 0;
  while (in >> area >> instance >> bits) {
    if (area >= heights.size() || instance >= heights[area].size())
      fail("{}: instance heights name area {} instance {}, not of this plan", where, area,
           instance);
    heights[area][instance] = double(std::bit_cast<float>(bits));
  }
  if (!in.eof()) fail("{}: unreadable instance heights", where);
}

}  // namespace tw::detail
