#pragma once
// Boost.Geometry as terraweave uses it: the planar model types over double metres and the one
// conversion from Vec2, for the modules that index or intersect geometry (grown footprints,
// area filters, area leads). Header-only; a module includes it in its .cpp files only.

// GCC 12 sees maybe-uninitialized values inside Boost.Geometry's envelope and rescaling code
// once inlined (false positives in the library's headers); ours stays -Wall clean.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/segment.hpp>
#include <boost/geometry/index/rtree.hpp>
#pragma GCC diagnostic pop

#include "core/vec2.hpp"

namespace tw::geometry {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BgPoint = bg::model::d2::point_xy<double>;
using BgSegment = bg::model::segment<BgPoint>;
using BgBox = bg::model::box<BgPoint>;
using BgPolygon = bg::model::polygon<BgPoint>;
using BgLine = bg::model::linestring<BgPoint>;
using BgLines = bg::model::multi_linestring<BgLine>;

inline BgPoint to_bg(Vec2 p) {
  return {p.x, p.y};
}

}  // namespace tw::geometry
