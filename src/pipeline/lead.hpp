#pragma once
// A lead: the direction a synthesis is turned to over a polygon, as `kind: area` classes
// (pipeline/area_config.hpp) and network classes (pipeline/network_config.hpp) read it from
// `lead:`; pipeline/lead_direction.hpp finds its direction.
#include <string_view>

namespace tw {

enum class Lead {
  bearing,       // a fixed compass bearing
  long_axis,     // the polygon's principal axis
  nearest_road,  // the direction of the run's road segment nearest to the polygon
  contours,      // along the terrain's contours over the polygon (across the slope)
};

// "bearing", "long_axis", "nearest_road", "contours" (report.json's `lead`).
std::string_view lead_name(Lead lead);

}  // namespace tw
