#pragma once
// The growth both `terraweave grow` and a run's grown classes use (docs/ornaments.md): a region
// of a heightfield as a mesh, the allowed mask (inside the region, off the avoided features, off
// nodata), FloralSurf's space filling on it and the coverage; and the GeoPackage of the lines.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "ornament/element.hpp"
#include "ornament/grow.hpp"
#include "pipeline/grow_config.hpp"
#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"

namespace tw {

// The heat method factors a sparse matrix of the mesh's vertices: past a few million that
// takes minutes and gigabytes, so the region must be cut or coarsened.
inline constexpr std::int64_t kMaxGrowVertices = 4'000'000;

// The space filling's parameters of `settings`.
GrowthParams growth_params(const GrowSettings& settings);
// The element set with the settings' clearance, when they give one.
ElementSet with_settings(ElementSet set, const GrowSettings& settings);

// [minx, miny, maxx, maxy] as a rectangle.
Polygon box_polygon(const std::array<double, 4>& box);
// The grid window holding the polygons' outer rings (plus a vertex), clipped to the grid.
Window window_around(const std::vector<Polygon>& polygons, const GridSpec& grid);

struct GrownRegion {
  GrowthResult grown;
  double coverage = 0.0, coverage_radius = 0.0;
  double growth_ms = 0.0;  // the mesh, its factorization and the growth
  Raster<float> heights;   // the mesh's (nodata filled with the lowest height)
};

// Grows `set` over `region` on `window` of `grid`. `heights` is window-sized, NaN where nodata
// (forbidden, never read as a height); no line enters `avoided` (pixel-centre rule on the
// mesh, a coarse first filter that also steers the growth) nor, exactly in vector space, a
// footprint or cell of `keep_off`. Throws tw::Error starting with `subject` when the window is
// too large or all nodata.
GrownRegion grow_region(const ElementSet& set, const GrowSettings& settings, const GridSpec& grid,
                        const Window& window, Raster<float> heights,
                        const std::vector<Polygon>& region, const AvoidanceInputs& avoided,
                        const KeepOff& keep_off, const std::string& subject);

// The cells of `window` of `grid` where `heights` (window-sized) is nodata, as ForbiddenCells.
ForbiddenCells nodata_cells(const GridSpec& grid, const Window& window,
                            const Raster<float>& heights);

// The footprints of AvoidanceInputs' polygons and lines (each line buffered by half its width),
// ids in that order.
FootprintIndex footprints_of(const AvoidanceInputs& avoided);

// A grown kind's width in metres (hedge 2, wall 1, trail 2, ditch 1: apply_grown_defaults).
double grown_kind_width(const std::string& kind);

// One layer of ornaments.gpkg: the grown lines of one class (or of `terraweave grow`).
struct OrnamentLayer {
  std::string name;       // the layer: the class's name ("ornaments" for terraweave grow)
  std::string kind;       // hedge, wall, trail, ditch (or the class's line kind)
  double height_m = 0.0;  // the profile's raise (+) or carve (-), metres; 0 for graded lines
  const std::vector<GrownLine>* lines = nullptr;
  std::vector<std::int64_t> fids;  // one per line (empty: 1, 2, ...)
};

// LineString Z layers (fid, ornament, element, name, material, kind, height_m; Z: the surface)
// in `crs_wkt`; the same lines give the same bytes (a fixed gpkg_contents date).
void write_ornament_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                               const std::vector<OrnamentLayer>& layers);

}  // namespace tw
