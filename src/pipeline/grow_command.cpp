#include "pipeline/grow_command.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield_source.hpp"
#include "layers/layer_set.hpp"
#include "layers/write.hpp"
#include "ornament/grow.hpp"
#include "pipeline/detail/vector_inputs.hpp"
#include "raster/rasterize.hpp"

namespace tw {

namespace {

// The heat method factors a sparse matrix of the mesh's vertices: past a few million that
// takes minutes and gigabytes, so the region must be cut or coarsened.
constexpr std::int64_t kMaxGrowVertices = 4'000'000;

// "minx,miny,maxx,maxy" as a rectangle, or nullopt when the text is not four numbers.
std::optional<Polygon> bbox_polygon(const std::string& text) {
  double v[4];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4)
    return std::nullopt;
  if (!(v[0] < v[2] && v[1] < v[3])) fail("--region {}: expected minx,miny,maxx,maxy", text);
  return Polygon{{{v[0], v[1]}, {v[2], v[1]}, {v[2], v[3]}, {v[0], v[3]}}};
}

std::vector<Polygon> region_polygons(const GrowCommand& c, const Heightfield& frame,
                                     Warnings& warnings) {
  if (auto box = bbox_polygon(c.region)) return {*box};
  std::vector<Polygon> out;
  for (PolygonFeature& f : read_polygon_features(detail::vector_source(c.region, c.where), frame,
                                                 "grow.region", warnings)) {
    out.emplace_back(f.rings.begin(), f.rings.end());
  }
  if (out.empty()) fail("--region {}: no polygon inside the DEM", c.region);
  return out;
}

// The grid window holding the polygons (clipped to the grid).
Window window_around(const std::vector<Polygon>& polygons, const GridSpec& grid) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Polygon& p : polygons)
    for (Vec2 v : p.front()) {
      const Vec2 px = grid.world_to_pixel(v);
      x0 = std::min(x0, px.x), y0 = std::min(y0, px.y);
      x1 = std::max(x1, px.x), y1 = std::max(y1, px.y);
    }
  Window w;
  w.col0 = std::clamp(int(std::floor(x0)) - 1, 0, grid.width);
  w.row0 = std::clamp(int(std::floor(y0)) - 1, 0, grid.height);
  w.width = std::clamp(int(std::ceil(x1)) + 1, 0, grid.width) - w.col0;
  w.height = std::clamp(int(std::ceil(y1)) + 1, 0, grid.height) - w.row0;
  return w;
}

void write_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                      const std::string& kind, const std::vector<GrownLine>& lines) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!driver) fail("{}: GDAL has no GPKG driver", path.string());
  std::unique_ptr<GDALDataset> ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) fail("{}: cannot create the GeoPackage", path.string());
  OGRSpatialReference srs;
  srs.importFromWkt(crs_wkt.c_str());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = ds->CreateLayer("ornaments", &srs, wkbLineString25D, nullptr);
  if (!layer) fail("{}: cannot create layer 'ornaments'", path.string());
  for (const char* name : {"ornament", "element"}) {
    OGRFieldDefn field(name, OFTInteger);
    layer->CreateField(&field);
  }
  for (const char* name : {"name", "material", "kind"}) {
    OGRFieldDefn field(name, OFTString);
    layer->CreateField(&field);
  }
  if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  for (const GrownLine& line : lines) {
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("ornament", line.ornament);
    feature.SetField("element", line.element);
    feature.SetField("name", line.name.c_str());
    feature.SetField("material", line.material.c_str());
    feature.SetField("kind", kind.c_str());
    OGRLineString geometry;
    for (std::size_t k = 0; k < line.points.size(); ++k) {
      geometry.addPoint(line.points[k].x, line.points[k].y, line.heights[k]);
    }
    feature.SetGeometry(&geometry);
    if (layer->CreateFeature(&feature) != OGRERR_NONE)
      fail("{}: cannot write a line", path.string());
  }
  if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
}

}  // namespace

GrowCommandResult run_grow_command(const GrowCommand& c) {
  if (c.out.empty()) fail("grow: --out is required");
  const ElementSet set = read_element_set(c.element);
  Warnings warnings;
  HeightfieldOptions options;
  if (c.resolution > 0.0) options.resolution = c.resolution;
  options.resampling = Resampling::cubic;
  const std::unique_ptr<HeightfieldSource> dem = open_heightfield(c.dem, options, warnings);
  const Heightfield frame = dem->without_pixels();
  const GridSpec& grid = frame.grid;
  const std::vector<Polygon> region = region_polygons(c, frame, warnings);
  const Window window = window_around(region, grid);
  if (window.width < 2 || window.height < 2) fail("--region {}: outside the DEM", c.region);
  // The mesh, its heat-method factorization and the masks follow the region's window.
  if (std::int64_t(window.width) * window.height > kMaxGrowVertices) {
    fail(
        "--region {}: {}x{} mesh vertices, at most {} (a coarser --resolution or a smaller "
        "region)",
        c.region, window.width, window.height, kMaxGrowVertices);
  }

  Raster<float> heights = dem->read(window);
  Raster<std::uint8_t> allowed;
  burn_polygons(region, grid, window, allowed, 1);
  if (!c.avoid.empty()) {
    const AvoidanceInputs avoided =
        detail::avoided_features(frame, c.avoid, c.avoid_width, "grow.avoid", warnings);
    const AvoidanceMap map = build_avoidance_map(avoided, grid, window);
    for (std::size_t i = 0; i < allowed.pixels.size(); ++i)
      allowed.pixels[i] &= !map.forbidden.pixels[i];
  }
  // Nodata is never a height: those cells are forbidden, and the mesh stands on the lowest
  // height there so the heat method sees a finite surface.
  float lowest = std::numeric_limits<float>::infinity();
  for (float h : heights.pixels)
    if (std::isfinite(h)) lowest = std::min(lowest, h);
  if (!std::isfinite(lowest)) fail("{}: only nodata under --region {}", c.dem, c.region);
  for (std::size_t i = 0; i < heights.pixels.size(); ++i) {
    if (!std::isfinite(heights.pixels[i])) {
      heights.pixels[i] = lowest;
      allowed.pixels[i] = 0;
    }
  }

  const auto started = std::chrono::steady_clock::now();
  const TerrainSurface surface(heights, grid, window);
  GrowthParams params;
  params.seed = c.seed;
  params.trials = c.trials;
  params.max_ornaments = c.max_ornaments;
  params.alignment = c.contour ? OrnamentAlignment::contour : OrnamentAlignment::growth;
  params.selection =
      c.first_fit ? CandidateSelection::first_fit : CandidateSelection::best_mean_distance;
  const GrowthResult grown = grow_ornaments(surface, allowed, set, params);

  GrowCommandResult result;
  result.growth_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  result.ornaments = grown.ornaments;
  result.elements = grown.elements;
  result.lines = int(grown.lines.size());
  result.rejected_crossing = grown.rejected_crossing;
  result.rejected_forbidden = grown.rejected_forbidden;
  result.rejected_untraceable = grown.rejected_untraceable;
  result.width = window.width;
  result.height = window.height;
  result.coverage_radius = c.coverage_radius > 0.0 ? c.coverage_radius : set.scale_m / 2;
  result.coverage = ornament_coverage(surface, allowed, grown.lines, result.coverage_radius);

  LayerSet preview;
  preview.grid = grid;
  preview.grid.width = window.width;
  preview.grid.height = window.height;
  preview.grid.origin_x = grid.origin_x + window.col0 * grid.pixel_width;
  preview.grid.origin_y = grid.origin_y - window.row0 * grid.pixel_height;
  preview.crs_wkt = frame.crs_wkt;
  preview.layers.push_back(height_layer(heights));
  std::vector<std::vector<Vec2>> drawn;
  for (const GrownLine& line : grown.lines) drawn.push_back(line.points);

  OutputTransaction transaction;
  write_geopackage(transaction.stage(c.out / "ornaments.gpkg"), frame.crs_wkt, set.kind,
                   grown.lines);
  write_preview_png(preview, transaction.stage(c.out / "preview.png"), drawn);
  transaction.commit();
  logger().info(
      "grow: {} ornaments, {} elements, {} lines over {}x{} vertices in {:.0f} ms; "
      "coverage within {:.1f} m: {:.3f}",
      result.ornaments, result.elements, result.lines, window.width, window.height,
      result.growth_ms, result.coverage_radius, result.coverage);
  return result;
}

}  // namespace tw
