#pragma once
// A heightfield opened once and read window by window. Its grid, CRS and nodata are known
// without reading a pixel; any window holds the same bytes as the matching window of the whole
// read (read_heightfield is this source's whole window), so a tile, a feature's corridor or a
// block of a cache reads only what it covers: memory follows the work, not the world.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield.hpp"

namespace tw {

class HeightfieldSource {
 public:
  virtual ~HeightfieldSource() = default;
  HeightfieldSource(const HeightfieldSource&) = delete;
  HeightfieldSource& operator=(const HeightfieldSource&) = delete;

  const GridSpec& grid() const { return grid_; }
  const std::string& crs_wkt() const { return crs_wkt_; }
  const std::optional<double>& nodata_value() const { return nodata_value_; }
  const std::string& name() const { return name_; }  // path or "generated:seed=N"

  // Heights of `window` (metres, NaN for nodata); throws tw::Error naming the source when the
  // window leaves the grid or the read fails. Safe to call from several threads.
  Raster<float> read(const Window& window) const;
  // Cells read so far, over every window: what a bounded stage touched (tests assert on it).
  std::int64_t cells_read() const { return cells_read_.load(); }
  // Grid, CRS, nodata and name without pixels: what vector ingest needs to place features.
  Heightfield without_pixels() const;

 protected:
  HeightfieldSource(GridSpec grid, std::string crs_wkt, std::optional<double> nodata_value,
                    std::string name);
  // `window` lies inside the grid and is not empty.
  virtual Raster<float> read_window(const Window& window) const = 0;

 private:
  GridSpec grid_;
  std::string crs_wkt_;
  std::optional<double> nodata_value_;
  std::string name_;
  mutable std::atomic<std::int64_t> cells_read_{0};
};

// Opens band 1 of a GDAL raster with read_heightfield's rules (same grid, resampling, warping,
// units and errors); reads no pixel, so neither the all-nodata check nor the height bound
// covers cells no window has read yet (a window beyond kMaxAbsHeight still throws).
std::unique_ptr<HeightfieldSource> open_heightfield(const std::string& path,
                                                    const HeightfieldOptions& options,
                                                    Warnings& warnings);

// generate_heightfield window by window (a window of a generated world is the same window of
// the world, by construction of the noise). Validates the parameters as generate_heightfield.
std::unique_ptr<HeightfieldSource> open_generated_heightfield(const GeneratedTerrain& params);
// The same with the WKT that params.crs was found to be before (a plan's own, checked against
// the plan's hash): the other parameters are checked, PROJ is not asked again (its database
// lookup was 3 % of a render-tile, issue #23 item 4).
std::unique_ptr<HeightfieldSource> open_generated_heightfield(const GeneratedTerrain& params,
                                                              std::string checked_crs_wkt);

// A heightfield already in memory; `heightfield` (or `height`) must outlive the source.
std::unique_ptr<HeightfieldSource> in_memory_heightfield(const Heightfield& heightfield);
std::unique_ptr<HeightfieldSource> in_memory_heightfield(const Raster<float>& height,
                                                         const GridSpec& grid);

// Throws tw::Error naming the source when every cell is nodata; reads strips of a few rows
// until it meets a height (for a usual DEM, the first strip).
void require_some_height(const HeightfieldSource& source);

// The whole grid; throws tw::Error naming the source when every cell is nodata.
Heightfield read_whole_heightfield(const HeightfieldSource& source);

// A window with its own grid (origin moved onto the window's north-west corner) and the
// source's CRS, nodata and name.
Heightfield read_heightfield_window(const HeightfieldSource& source, const Window& window);

}  // namespace tw
