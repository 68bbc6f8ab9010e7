#include "geo/heightfield_source.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw {
namespace {

// A heightfield in memory: windows are copies of its cells.
class InMemorySource final : public HeightfieldSource {
 public:
  InMemorySource(const Raster<float>& height, const GridSpec& grid, std::string crs_wkt,
                 std::optional<double> nodata_value, std::string name)
      : HeightfieldSource(grid, std::move(crs_wkt), nodata_value, std::move(name)),
        height_(height) {
    if (height.width != grid.width || height.height != grid.height)
      fail("{}: height raster is {} x {}, the grid is {} x {}", this->name(), height.width,
           height.height, grid.width, grid.height);
  }

 protected:
  Raster<float> read_window(const Window& w) const override {
    Raster<float> out(w.width, w.height);
    for (int r = 0; r < w.height; ++r) {
      const auto row = height_.pixels.begin() + std::ptrdiff_t(w.row0 + r) * height_.width + w.col0;
      std::copy(row, row + w.width, out.pixels.begin() + std::ptrdiff_t(r) * w.width);
    }
    return out;
  }

 private:
  const Raster<float>& height_;
};

}  // namespace

HeightfieldSource::HeightfieldSource(GridSpec grid, std::string crs_wkt,
                                     std::optional<double> nodata_value, std::string name)
    : grid_(grid),
      crs_wkt_(std::move(crs_wkt)),
      nodata_value_(nodata_value),
      name_(std::move(name)) {}

Raster<float> HeightfieldSource::read(const Window& window) const {
  if (window.col0 < 0 || window.row0 < 0 || window.width < 0 || window.height < 0 ||
      window.col_end() > grid_.width || window.row_end() > grid_.height) {
    fail("{}: window ({}, {}, {} x {}) is outside the {} x {} grid", name_, window.col0,
         window.row0, window.width, window.height, grid_.width, grid_.height);
  }
  if (window.width == 0 || window.height == 0) return Raster<float>(window.width, window.height);
  cells_read_ += std::int64_t(window.width) * window.height;
  return read_window(window);
}

Heightfield HeightfieldSource::without_pixels() const {
  Heightfield field;
  field.grid = grid_;
  field.crs_wkt = crs_wkt_;
  field.nodata_value = nodata_value_;
  field.source = name_;
  return field;
}

std::unique_ptr<HeightfieldSource> in_memory_heightfield(const Heightfield& heightfield) {
  return std::make_unique<InMemorySource>(heightfield.height, heightfield.grid, heightfield.crs_wkt,
                                          heightfield.nodata_value, heightfield.source);
}

std::unique_ptr<HeightfieldSource> in_memory_heightfield(const Raster<float>& height,
                                                         const GridSpec& grid) {
  return std::make_unique<InMemorySource>(height, grid, "", std::nullopt, "heights in memory");
}

namespace {
[[noreturn]] void fail_all_nodata(const HeightfieldSource& source) {
  fail("{}: every cell is nodata; there is no terrain to work on", source.name());
}
bool any_height(const Raster<float>& r) {
  return std::any_of(r.pixels.begin(), r.pixels.end(), [](float h) { return !std::isnan(h); });
}
}  // namespace

void require_some_height(const HeightfieldSource& source) {
  const GridSpec& g = source.grid();
  constexpr int kStripRows = 16;
  for (int row = 0; row < g.height; row += kStripRows)
    if (any_height(source.read({0, row, g.width, std::min(kStripRows, g.height - row)}))) return;
  fail_all_nodata(source);
}

Heightfield read_whole_heightfield(const HeightfieldSource& source) {
  Heightfield field = read_heightfield_window(source, Window::whole(source.grid()));
  if (!any_height(field.height)) fail_all_nodata(source);
  return field;
}

Heightfield read_heightfield_window(const HeightfieldSource& source, const Window& window) {
  Heightfield field = source.without_pixels();
  field.height = source.read(window);
  const Vec2 corner = source.grid().pixel_to_world({double(window.col0), double(window.row0)});
  field.grid = {window.width,
                window.height,
                corner.x,
                corner.y,
                source.grid().pixel_width,
                source.grid().pixel_height};
  return field;
}

}  // namespace tw
