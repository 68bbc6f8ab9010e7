#pragma once
// A decorative element drawn on the surface (FloralSurf Section 3.2): its control points mapped
// from the growth frame by straightest geodesics in polar coordinates (distance and angle, the
// exponential map), its splines traced as geodesic Bézier curves by de Casteljau subdivision
// with geodesic midpoints (Mancinelli et al. 2022, whose splines the paper uses).
#include <optional>
#include <string>
#include <vector>

#include "ornament/element.hpp"
#include "ornament/surface.hpp"

namespace tw {

struct SurfaceCurve {
  std::string material;
  std::vector<SurfacePoint> points;  // the subdivided control polygon, ends on the curve
};

struct TracedGrowthPoint {
  std::string tag;
  int priority = 0;
  SurfaceFrame frame;  // at the spline end; heading = the growth direction on the surface
};

struct TracedElement {
  std::vector<SurfaceCurve> curves;
  std::vector<TracedGrowthPoint> growth_points;  // those whose frame stays on the surface
};

// `frame` is where the element's origin goes and where its +x axis points; the element is
// scaled by metres_per_unit and turned by `rotation` radians about its origin first.
// `depth` subdivision levels give 3 * 2^depth segments per cubic. nullopt when a control
// point or a midpoint cannot be traced (the element leaves the window).
std::optional<TracedElement> trace_element(const TerrainSurface& surface,
                                           const DecorativeElement& element,
                                           const SurfaceFrame& frame, double metres_per_unit,
                                           double rotation, int depth = 3);

}  // namespace tw
