#include "network/preview.hpp"

#include <gdal_priv.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/grid.hpp"
#include "raster/rasterize.hpp"

namespace tw {

void write_network_png(const std::filesystem::path& path, const std::vector<PreviewPanel>& panels,
                       int size_px) {
  struct Frame {
    GridSpec grid;
  };
  std::vector<GridSpec> grids;
  int total_w = 0, max_h = 0;
  const int gap = 12;
  for (const PreviewPanel& panel : panels) {
    Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    const auto extend = [&](Vec2 p) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    };
    for (const Polygon& polygon : panel.region)
      for (Vec2 p : polygon.front()) extend(p);
    if (panel.region.empty())
      for (const PreviewLayer& l : panel.layers)
        for (Vec2 p : l.network->nodes) extend(p);
    if (!(hi.x > lo.x && hi.y > lo.y)) lo = {0, 0}, hi = {1, 1};
    const double pixel = std::max(hi.x - lo.x, hi.y - lo.y) / (size_px - 8);
    GridSpec g;
    g.width = int(std::ceil((hi.x - lo.x) / pixel)) + 8;
    g.height = int(std::ceil((hi.y - lo.y) / pixel)) + 8;
    g.origin_x = lo.x - 4 * pixel;
    g.origin_y = hi.y + 4 * pixel;
    g.pixel_width = g.pixel_height = pixel;
    grids.push_back(g);
    total_w += g.width + (total_w > 0 ? gap : 0);
    max_h = std::max(max_h, g.height);
  }
  std::vector<std::uint8_t> rgb(std::size_t(total_w) * std::size_t(max_h) * 3, 255);
  int x0 = 0;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const GridSpec& g = grids[p];
    const Window whole = Window::whole(g);
    const auto paint = [&](const Raster<std::uint8_t>& mask, std::array<std::uint8_t, 3> c) {
      for (int r = 0; r < mask.height; ++r)
        for (int col = 0; col < mask.width; ++col)
          if (mask.at(col, r))
            for (int k = 0; k < 3; ++k)
              rgb[(std::size_t(r) * std::size_t(total_w) + std::size_t(x0 + col)) * 3 +
                  std::size_t(k)] = c[std::size_t(k)];
    };
    if (!panels[p].region.empty()) {
      Raster<std::uint8_t> inside;
      burn_polygons(panels[p].region, g, whole, inside, 1);
      paint(inside, {240, 238, 226});
    }
    if (const ForbiddenMask* f = panels[p].forbidden) {
      Raster<std::uint8_t> mask(g.width, g.height, 0);
      for (int r = 0; r < g.height; ++r)
        for (int col = 0; col < g.width; ++col) {
          const Vec2 px = f->grid.world_to_pixel(g.pixel_centre_world(col, r));
          const int fc = int(std::floor(px.x)), fr = int(std::floor(px.y));
          mask.at(col, r) = f->cells.inside(fc, fr) && f->cells.at(fc, fr) != 0;
        }
      paint(mask, {244, 196, 190});
    }
    for (const PreviewLayer& layer : panels[p].layers) {
      std::vector<std::vector<Vec2>> lines;
      for (const NetworkEdge& e : layer.network->edges) lines.push_back(e.points);
      Raster<std::uint8_t> mask;
      burn_buffered_lines(lines, std::vector<double>(lines.size(), layer.width_px * g.pixel_width),
                          g, whole, mask, 1);
      paint(mask, layer.colour);
    }
    x0 += g.width + gap;
  }
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
  if (!mem || !png) fail("{}: GDAL has no PNG driver", path.string());
  GDALDataset* ds = mem->Create("", total_w, max_h, 3, GDT_Byte, nullptr);
  for (int b = 0; b < 3; ++b)
    if (ds->GetRasterBand(b + 1)->RasterIO(GF_Write, 0, 0, total_w, max_h, rgb.data() + b, total_w,
                                           max_h, GDT_Byte, 3,
                                           std::int64_t(total_w) * 3) != CE_None)
      fail("{}: cannot draw the preview", path.string());
  GDALDataset* out = png->CreateCopy(path.string().c_str(), ds, FALSE, nullptr, nullptr, nullptr);
  GDALClose(ds);
  if (!out) fail("{}: cannot write: {}", path.string(), CPLGetLastErrorMsg());
  GDALClose(out);
  std::error_code ignored;
  std::filesystem::remove(path.string() + ".aux.xml", ignored);
}

}  // namespace tw
