#include "pipeline/grow_region.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "geo/geopackage.hpp"
#include "ornament/surface.hpp"
#include "pipeline/methods/grown/grown_config.hpp"
#include "raster/rasterize.hpp"

namespace tw {

GrowthParams growth_params(const GrowSettings& s) {
  GrowthParams params;
  params.seed = s.seed;
  params.trials = s.trials;
  params.max_ornaments = s.max_ornaments;
  params.max_elements = s.max_elements;
  params.alignment = s.contour ? OrnamentAlignment::contour : OrnamentAlignment::growth;
  params.selection =
      s.first_fit ? CandidateSelection::first_fit : CandidateSelection::best_mean_distance;
  return params;
}

ElementSet with_settings(ElementSet set, const GrowSettings& s) {
  if (s.clearance) set.clearance_m = *s.clearance;
  return set;
}

Polygon box_polygon(const std::array<double, 4>& v) {
  return Polygon{{{v[0], v[1]}, {v[2], v[1]}, {v[2], v[3]}, {v[0], v[3]}}};
}

Window window_around(const std::vector<Polygon>& polygons, const GridSpec& grid) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Polygon& p : polygons)
    for (Vec2 v : p.front()) {
      const Vec2 px = grid.world_to_pixel(v);
      x0 = std::min(x0, px.x), y0 = std::min(y0, px.y);
      x1 = std::max(x1, px.x), y1 = std::max(y1, px.y);
    }
  Window w;
  if (!std::isfinite(x0)) return w;
  w.col0 = std::clamp(int(std::floor(x0)) - 1, 0, grid.width);
  w.row0 = std::clamp(int(std::floor(y0)) - 1, 0, grid.height);
  w.width = std::clamp(int(std::ceil(x1)) + 1, 0, grid.width) - w.col0;
  w.height = std::clamp(int(std::ceil(y1)) + 1, 0, grid.height) - w.row0;
  return w;
}

GrownRegion grow_region(const ElementSet& set, const GrowSettings& settings, const GridSpec& grid,
                        const Window& window, Raster<float> heights,
                        const std::vector<Polygon>& region, const AvoidanceInputs& avoided,
                        const KeepOff& keep_off, const std::string& subject) {
  if (window.width < 2 || window.height < 2)
    fail("{}: the region is outside the heightfield", subject);
  // The mesh, its heat-method factorization and the masks follow the region's window.
  if (std::int64_t(window.width) * window.height > kMaxGrowVertices) {
    fail("{}: {}x{} mesh vertices, at most {} (a coarser resolution or a smaller region)", subject,
         window.width, window.height, kMaxGrowVertices);
  }
  Raster<std::uint8_t> allowed;
  burn_polygons(region, grid, window, allowed, 1);
  if (!avoided.polygons.empty() || !avoided.lines.empty()) {
    const AvoidanceMap map = build_avoidance_map(avoided, grid, window);
    for (std::size_t i = 0; i < allowed.pixels.size(); ++i)
      allowed.pixels[i] &= !map.forbidden.pixels[i];
  }
  // Nodata is never a height: those cells are forbidden, and the mesh stands on the lowest
  // height there so the heat method sees a finite surface.
  float lowest = std::numeric_limits<float>::infinity();
  for (float h : heights.pixels)
    if (std::isfinite(h)) lowest = std::min(lowest, h);
  if (!std::isfinite(lowest)) fail("{}: only nodata under the region", subject);
  for (std::size_t i = 0; i < heights.pixels.size(); ++i) {
    if (!std::isfinite(heights.pixels[i])) {
      heights.pixels[i] = lowest;
      allowed.pixels[i] = 0;
    }
  }

  GrownRegion out;
  const auto started = std::chrono::steady_clock::now();
  const TerrainSurface surface(heights, grid, window);
  out.grown = grow_ornaments(surface, allowed, set, growth_params(settings), keep_off);
  out.growth_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  out.coverage_radius = settings.coverage_radius > 0.0 ? settings.coverage_radius : set.scale_m / 2;
  out.coverage = ornament_coverage(surface, allowed, out.grown.lines, out.coverage_radius);
  out.heights = std::move(heights);
  return out;
}

ForbiddenCells nodata_cells(const GridSpec& grid, const Window& window,
                            const Raster<float>& heights) {
  ForbiddenCells cells{grid, window, Raster<std::uint8_t>(window.width, window.height)};
  for (std::size_t i = 0; i < heights.pixels.size(); ++i)
    cells.allowed.pixels[i] = std::isfinite(heights.pixels[i]);
  return cells;
}

FootprintIndex footprints_of(const AvoidanceInputs& avoided) {
  FootprintIndex index;
  for (const Polygon& p : avoided.polygons) index.add_polygon(p);
  for (std::size_t i = 0; i < avoided.lines.size(); ++i)
    index.add_line(avoided.lines[i], 0.5 * avoided.line_widths[i]);
  return index;
}

double grown_kind_width(const std::string& kind) {
  FeatureClassConfig c;
  detail::apply_grown_defaults(kind, c);
  return c.width;
}

void write_ornament_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                               const std::vector<OrnamentLayer>& layers) {
  GeoPackageWriter gpkg = create_geopackage(path, crs_wkt);
  for (const OrnamentLayer& l : layers) {
    OGRLayer* layer = &gpkg.create_layer(l.name, wkbLineString25D);
    gpkg.add_fields(*layer, {{"ornament", OFTInteger},
                             {"element", OFTInteger},
                             {"name", OFTString},
                             {"material", OFTString},
                             {"kind", OFTString},
                             {"height_m", OFTReal}});
    if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
    for (std::size_t i = 0; i < l.lines->size(); ++i) {
      const GrownLine& line = (*l.lines)[i];
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetFID(l.fids.empty() ? GIntBig(i + 1) : GIntBig(l.fids[i]));
      feature.SetField("ornament", line.ornament);
      feature.SetField("element", line.element);
      feature.SetField("name", line.name.c_str());
      feature.SetField("material", line.material.c_str());
      feature.SetField("kind", l.kind.c_str());
      feature.SetField("height_m", l.height_m);
      OGRLineString geometry;
      for (std::size_t k = 0; k < line.points.size(); ++k)
        geometry.addPoint(line.points[k].x, line.points[k].y, line.heights[k]);
      feature.SetGeometry(&geometry);
      if (layer->CreateFeature(&feature) != OGRERR_NONE)
        fail("{}: cannot write a line of '{}'", path.string(), l.name);
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  }
}

}  // namespace tw
