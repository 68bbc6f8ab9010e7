#include "pipeline/lead.hpp"

namespace tw {

std::string_view lead_name(Lead lead) {
  switch (lead) {
    case Lead::bearing:
      return "bearing";
    case Lead::long_axis:
      return "long_axis";
    case Lead::nearest_road:
      return "nearest_road";
    case Lead::contours:
      return "contours";
  }
  return "";
}

}  // namespace tw
