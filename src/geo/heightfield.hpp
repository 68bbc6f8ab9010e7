#pragma once
// The heightfield every stage works on: a north-up grid in a metric CRS, heights in metres,
// NaN for nodata. Read from any raster GDAL opens (warped into a local metric frame when the
// source is geographic, not in metres, or rotated) or generated from a seed.
#include <cstdint>
#include <optional>
#include <string>

#include "core/grid.hpp"
#include "core/warnings.hpp"

namespace tw {

// Heights beyond +-kMaxAbsHeight metres are refused on reading (they are undeclared nodata
// values such as -3.4e38, or corrupt data) and generated relief is capped at
// kMaxGeneratedRelief: every later difference, slope and sum of heights stays finite.
inline constexpr double kMaxAbsHeight = 1e5;
inline constexpr double kMaxGeneratedRelief = 1e5;

struct Heightfield {
  GridSpec grid;                       // north-up, metric (metres), square-ish pixels
  std::string crs_wkt;                 // WKT of the grid's (metric) CRS
  Raster<float> height;                // metres; NaN marks nodata (never a height)
  std::optional<double> nodata_value;  // the source's nodata value, for writing outputs
  std::string source;                  // path or "generated:seed=N" for messages and reports
};

// How a heightfield is read between its cells when it is warped or resampled.
enum class Resampling {
  bilinear,  // continuous heights, slopes that break at every source cell (faceted light)
  cubic,     // Catmull-Rom (GDAL's "cubic"): continuous slopes, exact on quadratics
};

struct HeightfieldOptions {
  // Output pixel size in metres; default: the source's, in metres (at the centre of the DEM
  // when the source is geographic).
  std::optional<double> resolution;
  Resampling resampling = Resampling::bilinear;
  // The CRS of the grid: "" = a metric north-up DEM keeps its own, a geographic one goes to
  // the UTM zone of its centre (as "utm"), any other (feet, rotated) to a local transverse
  // Mercator centred on it (as "local" does for every DEM); "utm" = the UTM
  // zone of the DEM's centre (utm_zone_epsg); else any projected CRS in metres PROJ reads
  // (EPSG:2169, WKT, a PROJ string), which every DEM not already in it is warped to.
  std::string crs;
};

// "EPSG:326zz" (north) or "EPSG:327zz" (south): the UTM zone holding (lon, lat) on WGS84
// (the regular 6-degree zones; Norway's and Svalbard's exceptions are not applied).
std::string utm_zone_epsg(double lon_degrees, double lat_degrees);

// Reads band 1 of a GDAL raster. A metric north-up DEM keeps its grid and CRS (resampled by
// geo/resample.hpp when options.resolution is set: options.resampling, averaged when coarser,
// nodata-aware); a geographic,
// non-metre or rotated one (or any DEM when options.crs names another CRS) is warped
// (options.resampling, nodata kept) into options.crs (default: the UTM zone of its centre;
// "local": local_transverse_mercator_wkt() centred on the DEM, geo/metric_frame.hpp), with the
// source's pixel size at its centre measured as geodesics, covering its whole footprint. Heights in
// feet (GDAL unit type "ft", "US survey foot") become metres. Throws tw::Error naming the path when
// the file cannot be read, has no CRS, holds nothing but nodata or a height beyond kMaxAbsHeight,
// or when the resolution gives a grid under one cell or over kMaxGridCells
// (core/grid_limits.hpp). An unknown height unit is taken as metres with an `unknown_unit`
// warning (subject `heightfield`).
Heightfield read_heightfield(const std::string& path, const HeightfieldOptions& options,
                             Warnings& warnings);
// The same, its warnings only logged.
Heightfield read_heightfield(const std::string& path, const HeightfieldOptions& options = {});

struct GeneratedTerrain {
  int width = 512;
  int height = 512;
  double pixel_size = 10.0;  // metres
  std::uint64_t seed = 1;
  double relief = 150.0;  // metres between the lowest and highest possible height
  std::string crs = "EPSG:32631";
  double origin_x = 500000;      // world x of the left edge
  double origin_y = 5000000;     // world y of the top edge
  double feature_size = 2560.0;  // metres spanned by the largest hills
};

// Seeded fractal terrain (gradient noise, fBm octaves) from an integer hash: the same
// parameters give the same bytes on every platform and thread count. The noise is a function
// of the world pixel, so a tile (same seed, pixel size and feature size, origin on the same
// pixel lattice) equals the matching window of a larger generated world.
Heightfield generate_heightfield(const GeneratedTerrain& params);

}  // namespace tw
