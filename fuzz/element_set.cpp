// Fuzz target: tw::parse_element_set on arbitrary text. What it accepts keeps the promises the
// growth relies on: finite control points, 3n + 1 of them per spline and not all at one place,
// sizes > 0, a seed tag some element answers. Anything else is a tw::Error naming the key.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ornament/element.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tw::ElementSet set;
  try {
    set =
        tw::parse_element_set(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const tw::Error&) {
    return 0;
  }
  if (tw::elements_with_tag(set, set.seed_tag).empty())
    tw::fuzz::broken_promise("no element answers the seed tag");
  tw::fuzz::expect_finite(set.scale_m, "scale_m");
  if (!(set.scale_m > 0.0)) tw::fuzz::broken_promise("scale_m <= 0");
  for (const tw::DecorativeElement& e : set.elements) {
    for (const tw::BezierSpline& s : e.splines) {
      if (s.control_points.size() < 4 || (s.control_points.size() - 1) % 3 != 0)
        tw::fuzz::broken_promise("a spline without 3n + 1 control points");
      bool moves = false;
      for (const tw::Vec2 p : s.control_points) {
        tw::fuzz::expect_finite(p.x, "control point x");
        tw::fuzz::expect_finite(p.y, "control point y");
        moves = moves || p.x != s.control_points.front().x || p.y != s.control_points.front().y;
      }
      if (!moves) tw::fuzz::broken_promise("a spline of one point");
    }
    for (const double size : e.sizes)
      if (!(size > 0.0) || !std::isfinite(size)) tw::fuzz::broken_promise("a size <= 0");
  }
  return 0;
}
