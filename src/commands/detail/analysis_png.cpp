#include "commands/detail/analysis_png.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "image/image_io.hpp"
#include "raster/rasterize.hpp"

namespace tw::detail {

namespace {

using Rgb = std::array<std::uint8_t, 3>;

constexpr std::array<Rgb, 8> kPalette{{{31, 119, 180},
                                       {214, 39, 40},
                                       {44, 160, 44},
                                       {148, 103, 189},
                                       {255, 127, 14},
                                       {23, 190, 207},
                                       {140, 86, 75},
                                       {227, 119, 194}}};

Rgb pale(Rgb c) {
  return {std::uint8_t(255 - (255 - c[0]) / 4), std::uint8_t(255 - (255 - c[1]) / 4),
          std::uint8_t(255 - (255 - c[2]) / 4)};
}

// One panel: the input space [0, 1]^2 (y up) on a grid, drawn with geometry in sketch units.
class Panel {
 public:
  explicit Panel(int size) : size_(size), rgb_(std::size_t(size) * size * 3, 255) {
    grid_.width = grid_.height = size;
    grid_.origin_x = 0.0, grid_.origin_y = 1.0;
    grid_.pixel_width = grid_.pixel_height = 1.0 / size;
  }

  void lines(const std::vector<std::vector<Vec2>>& lines, double width, Rgb colour) {
    Raster<std::uint8_t> mask;
    burn_buffered_lines(lines, std::vector<double>(lines.size(), std::max(width, 1.5 / size_)),
                        grid_, Window::whole(grid_), mask, 1);
    paint(mask, colour);
  }
  void polygon(const std::vector<Vec2>& ring, Rgb colour) {
    Raster<std::uint8_t> mask;
    burn_polygons({Polygon{ring}}, grid_, Window::whole(grid_), mask, 1);
    paint(mask, colour);
  }
  void dot(Vec2 p, double radius, Rgb colour) { lines({{p, p}}, 2.0 * radius, colour); }
  // A band across `line` between offsets lo and hi, long enough to cross the square.
  void band(const SupportLine& line, double lo, double hi, Rgb colour) {
    const Vec2 n = perp(line.direction), d = line.direction * 2.0;
    polygon({line.point - d + n * lo, line.point + d + n * lo, line.point + d + n * hi,
             line.point - d + n * hi},
            colour);
  }
  void infinite_line(const SupportLine& line, double offset, double width, Rgb colour) {
    const Vec2 o = line.point + perp(line.direction) * offset, d = line.direction * 2.0;
    lines({{o - d, o + d}}, width, colour);
  }
  void frame() { lines({{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}}, 2.0 / size_, {120, 120, 120}); }
  const std::vector<std::uint8_t>& rgb() const { return rgb_; }

 private:
  void paint(const Raster<std::uint8_t>& mask, Rgb colour) {
    for (std::size_t i = 0; i < mask.pixels.size(); ++i)
      if (mask.pixels[i])
        for (std::size_t c = 0; c < 3; ++c) rgb_[3 * i + c] = colour[c];
  }
  int size_;
  GridSpec grid_;
  std::vector<std::uint8_t> rgb_;
};

std::vector<std::vector<Vec2>> strokes_of(const SupportHierarchy& h, const SketchShape& shape) {
  std::vector<std::vector<Vec2>> out;
  for (int s : shape.strokes) out.push_back(h.sketch.strokes[std::size_t(s)].points);
  return out;
}

void draw_strokes(Panel& p, const SupportHierarchy& h, Rgb colour) {
  for (const Stroke& s : h.sketch.strokes) p.lines({s.points}, s.thickness, colour);
}

}  // namespace

void write_analysis_png(const std::filesystem::path& path, const SupportHierarchy& h, int size) {
  const Rgb grey{150, 150, 150};
  std::vector<Panel> panels(5, Panel(size));
  // Strokes, coloured by material.
  std::vector<std::string> materials;
  for (const Stroke& s : h.sketch.strokes) {
    auto it = std::find(materials.begin(), materials.end(), s.material);
    if (it == materials.end()) it = materials.insert(materials.end(), s.material);
    panels[0].lines({s.points}, s.thickness, kPalette[std::size_t(it - materials.begin()) % 8]);
  }
  // Shapes: oriented boxes, central points, support segments; unbounded shapes as fibres.
  for (std::size_t i = 0; i < h.shapes.size(); ++i) {
    const SketchShape& shape = h.shapes[i];
    const Rgb c = kPalette[i % 8];
    const OrientedBox& b = shape.box;
    const Vec2 a = b.axis * b.half_length, n = perp(b.axis) * b.half_width;
    panels[1].polygon({b.center - a - n, b.center + a - n, b.center + a + n, b.center - a + n},
                      pale(c));
    panels[1].lines(strokes_of(h, shape), 0.004, c);
    if (shape.support == ShapeSupport::point) panels[1].dot(b.center, 0.008, {0, 0, 0});
    if (shape.support == ShapeSupport::segment)
      panels[1].lines({{b.center - a, b.center + a}}, 0.003, {0, 0, 0});
  }
  // Fibres and their ribbons (the extent of their shapes across the line).
  for (std::size_t i = 0; i < h.fibres.size(); ++i) {
    const Fibre& f = h.fibres[i];
    panels[2].band(f.line, f.extent.lo, f.extent.hi, pale(kPalette[i % 8]));
  }
  draw_strokes(panels[2], h, grey);
  for (std::size_t i = 0; i < h.fibres.size(); ++i)
    panels[2].infinite_line(h.fibres[i].line, 0.0, 0.004, kPalette[i % 8]);
  // Medians: the displacement area of each (its members' extents), the median line.
  for (std::size_t i = 0; i < h.medians.size(); ++i) {
    const Grouping& m = h.medians[i];
    double lo = INFINITY, hi = -INFINITY;
    for (const Interval& e : m.extents) lo = std::min(lo, e.lo), hi = std::max(hi, e.hi);
    if (std::isfinite(lo)) panels[3].band(m.line, lo, hi, pale(kPalette[i % 8]));
  }
  draw_strokes(panels[3], h, grey);
  for (std::size_t i = 0; i < h.medians.size(); ++i)
    panels[3].infinite_line(h.medians[i].line, 0.0, 0.006, kPalette[i % 8]);
  // Lead directions: their medians' bands in the lead's colour, the gaps between neighbours
  // hatched pale, and the direction itself through the square's centre.
  for (std::size_t i = 0; i < h.leads.size(); ++i) {
    const Grouping& lead = h.leads[i];
    const Rgb c = kPalette[i % 8];
    for (const Interval& e : lead.extents) panels[4].band(lead.line, e.lo, e.hi, pale(c));
  }
  draw_strokes(panels[4], h, grey);
  for (std::size_t i = 0; i < h.leads.size(); ++i) {
    const Grouping& lead = h.leads[i];
    const SupportLine through{{0.5, 0.5}, lead.line.direction};
    panels[4].infinite_line(through, 0.0, 0.012, kPalette[i % 8]);
    const Vec2 tip = Vec2{0.5, 0.5} + lead.line.direction * 0.45;
    const Vec2 back = lead.line.direction * -0.06, side = perp(lead.line.direction) * 0.04;
    panels[4].polygon({tip, tip + back + side, tip + back - side}, kPalette[i % 8]);
  }
  for (Panel& p : panels) p.frame();

  // Side by side with a gap of a tenth of a panel.
  const int gap = size / 10, width = 5 * size + 4 * gap;
  std::vector<std::uint8_t> rgb(std::size_t(width) * size * 3, 255);
  for (int k = 0; k < 5; ++k)
    for (int row = 0; row < size; ++row)
      std::copy_n(panels[std::size_t(k)].rgb().data() + std::size_t(row) * size * 3,
                  std::size_t(size) * 3,
                  rgb.data() + (std::size_t(row) * width + std::size_t(k) * (size + gap)) * 3);
  write_rgb8_image(path.string(), width, size, rgb.data(), path.string());
}

}  // namespace tw::detail
