#include "pipeline/area_output.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "geo/geopackage.hpp"
#include "image/image_io.hpp"
#include "pipeline/lead_direction.hpp"
#include "raster/rasterize.hpp"

namespace tw {

namespace {

std::string type_of(const ShapeInstance& i) {
  return fmt::format("shape_{}", i.shape);
}

// NaN when unknown.
double z_of(const AreaResult& r, std::size_t instance) {
  return instance < r.z.size() ? r.z[instance] : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

void write_area_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                           const std::vector<AreaResult>& results) {
  GeoPackageWriter gpkg = create_geopackage(path, crs_wkt);
  OGRLayer* strokes = &gpkg.create_layer("strokes", wkbLineString);
  const bool with_z =
      std::any_of(results.begin(), results.end(), [](const AreaResult& r) { return !r.z.empty(); });
  OGRLayer* instances = &gpkg.create_layer("instances", with_z ? wkbPoint25D : wkbPoint);
  gpkg.add_fields(*strokes, {{"class", OFTString},
                             {"polygon_fid", OFTInteger64},
                             {"instance", OFTInteger},
                             {"shape", OFTInteger},
                             {"material", OFTString},
                             {"width_m", OFTReal}});
  gpkg.add_fields(*instances, {{"class", OFTString},
                               {"polygon_fid", OFTInteger64},
                               {"shape", OFTInteger},
                               {"type", OFTString},
                               {"material", OFTString},
                               {"rotation_deg", OFTReal},
                               {"scale", OFTReal}});
  GDALDataset* dataset = &gpkg.dataset();
  dataset->StartTransaction();
  int base = 0;  // instance numbers run on across polygons
  // Millions of strokes take minutes: a line per tenth, with the time left.
  Progress progress("areas.gpkg", std::int64_t(results.size()));
  for (const AreaResult& r : results) {
    for (const PlacedStroke& s : r.pattern.strokes) {
      OGRFeature feature(strokes->GetLayerDefn());
      feature.SetField("class", r.area_class.c_str());
      feature.SetField("polygon_fid", GIntBig(r.fid));
      feature.SetField("instance", base + s.instance);
      feature.SetField("shape", r.pattern.instances[std::size_t(s.instance)].shape);
      feature.SetField("material", s.material.c_str());
      feature.SetField("width_m", s.width);
      OGRLineString line;
      for (Vec2 p : s.points) line.addPoint(p.x, p.y);
      feature.SetGeometry(&line);
      if (strokes->CreateFeature(&feature) != OGRERR_NONE) fail("{}: write failed", path.string());
    }
    for (std::size_t n = 0; n < r.pattern.instances.size(); ++n) {
      const ShapeInstance& i = r.pattern.instances[n];
      OGRFeature feature(instances->GetLayerDefn());
      feature.SetField("class", r.area_class.c_str());
      feature.SetField("polygon_fid", GIntBig(r.fid));
      feature.SetField("shape", i.shape);
      feature.SetField("type", type_of(i).c_str());
      feature.SetField("material", i.material.c_str());
      feature.SetField("rotation_deg", compass_degrees(i.rotation));
      feature.SetField("scale", i.scale);
      OGRPoint point(i.position.x, i.position.y);
      if (with_z) point.setZ(z_of(r, n));
      feature.SetGeometry(&point);
      if (instances->CreateFeature(&feature) != OGRERR_NONE)
        fail("{}: write failed", path.string());
    }
    base += int(r.pattern.instances.size());
    progress.advance();
  }
  if (dataset->CommitTransaction() != OGRERR_NONE) fail("{}: commit failed", path.string());
}

void write_instances_csv(const std::filesystem::path& path,
                         const std::vector<AreaResult>& results) {
  std::ofstream out(path);
  out << "x,y,z,rotation_deg,scale,type,material,class\n";
  for (const AreaResult& r : results) {
    for (std::size_t n = 0; n < r.pattern.instances.size(); ++n) {
      const ShapeInstance& i = r.pattern.instances[n];
      const double z = z_of(r, n);
      out << fmt::format("{:.3f},{:.3f},{},{:.3f},{:.6g},{},{},{}\n", i.position.x, i.position.y,
                         std::isfinite(z) ? fmt::format("{:.3f}", z) : "",
                         compass_degrees(i.rotation), i.scale, type_of(i), i.material,
                         r.area_class);
    }
  }
  out.close();
  if (!out) fail("{}: cannot write", path.string());
}

void write_instances_json(const std::filesystem::path& path,
                          const std::vector<AreaResult>& results) {
  // Rounded as in the CSV, so the two files say the same and diff cleanly between runs.
  const auto rounded = [](double v, int decimals) {
    return std::stod(fmt::format("{:.{}f}", v, decimals));
  };
  nlohmann::json instances = nlohmann::json::array();
  for (const AreaResult& r : results)
    for (std::size_t n = 0; n < r.pattern.instances.size(); ++n) {
      const ShapeInstance& i = r.pattern.instances[n];
      const double z = z_of(r, n);
      instances.push_back(
          {{"x", rounded(i.position.x, 3)},
           {"y", rounded(i.position.y, 3)},
           {"z", std::isfinite(z) ? nlohmann::json(rounded(z, 3)) : nlohmann::json()},
           {"rotation_deg", rounded(compass_degrees(i.rotation), 3)},
           {"scale", i.scale},
           {"type", type_of(i)},
           {"material", i.material},
           {"class", r.area_class}});
    }
  std::ofstream out(path);
  out << instances.dump(1) << '\n';
  out.close();
  if (!out) fail("{}: cannot write", path.string());
}

void write_area_preview(const std::filesystem::path& path, const std::vector<Polygon>& polygons,
                        const AvoidanceInputs& avoided, const std::vector<AreaResult>& results,
                        double resolution) {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (const Polygon& polygon : polygons)
    for (Vec2 p : polygon.front()) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  const double pixel = std::max(resolution, extent / 2048.0);  // at most 2048 px a side
  GridSpec grid;
  grid.width = std::max(1, int(std::ceil((hi.x - lo.x) / pixel)));
  grid.height = std::max(1, int(std::ceil((hi.y - lo.y) / pixel)));
  grid.origin_x = lo.x, grid.origin_y = hi.y;
  grid.pixel_width = grid.pixel_height = pixel;
  const Window whole = Window::whole(grid);
  std::vector<std::uint8_t> rgb(std::size_t(grid.width) * grid.height * 3, 255);
  const auto paint = [&](const Raster<std::uint8_t>& mask, std::array<std::uint8_t, 3> colour) {
    for (std::size_t i = 0; i < mask.pixels.size(); ++i)
      if (mask.pixels[i])
        for (int c = 0; c < 3; ++c) rgb[3 * i + std::size_t(c)] = colour[std::size_t(c)];
  };
  {  // field tint, then outlines
    Raster<std::uint8_t> inside;
    burn_polygons(polygons, grid, whole, inside, 1);
    paint(inside, {236, 240, 220});
    std::vector<std::vector<Vec2>> outlines;
    for (const Polygon& polygon : polygons)
      for (const Ring& ring : polygon) {
        outlines.push_back(ring);
        outlines.back().push_back(ring.front());
      }
    Raster<std::uint8_t> edges;
    burn_buffered_lines(outlines, std::vector<double>(outlines.size(), 1.5 * pixel), grid, whole,
                        edges, 1);
    paint(edges, {90, 90, 90});
    Raster<std::uint8_t> forbidden;
    burn_polygons(avoided.polygons, grid, whole, forbidden, 1);
    burn_buffered_lines(avoided.lines, avoided.line_widths, grid, whole, forbidden, 1);
    paint(forbidden, {244, 196, 190});
  }
  static const std::array<std::array<std::uint8_t, 3>, 6> palette{
      {{46, 110, 46}, {120, 72, 30}, {40, 80, 160}, {170, 40, 40}, {130, 60, 150}, {20, 140, 140}}};
  std::map<std::string, std::pair<std::vector<std::vector<Vec2>>, std::vector<double>>> by_material;
  for (const AreaResult& r : results)
    for (const PlacedStroke& s : r.pattern.strokes) {
      auto& [lines, widths] = by_material[s.material];
      lines.push_back(s.points);
      widths.push_back(std::max(s.width, pixel));
    }
  std::size_t colour = 0;
  for (const auto& [material, lines] : by_material) {
    Raster<std::uint8_t> mask;
    burn_buffered_lines(lines.first, lines.second, grid, whole, mask, 1);
    paint(mask, palette[colour++ % palette.size()]);
  }
  write_rgb8_image(path.string(), grid.width, grid.height, rgb.data(), path.string());
}

}  // namespace tw
