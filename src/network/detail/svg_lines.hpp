#pragma once
// Lines of an SVG drawing (an exemplar network drawn in Inkscape): <path> (M L H V C S Q T Z,
// absolute and relative; curves flattened), <line>, <polyline>, <polygon>. Anything else that
// draws (circle, rect, text, arcs, transforms) is an error naming the file and the element.
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace tw::detail {

struct SvgLine {
  std::int64_t element = 0;  // index of the element among the file's drawing elements
  std::vector<Vec2> points;  // SVG user units, y down
};

std::vector<SvgLine> read_svg_lines(const std::string& path, const std::string& subject);

}  // namespace tw::detail
