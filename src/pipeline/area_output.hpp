#pragma once
// Writers of `terraweave area`'s results: vectors (GeoPackage), engine instances (CSV), preview.
#include <filesystem>
#include <string>
#include <vector>

#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw {

struct AreaResult {
  std::string area_class;  // the class (a run's `kind: area` class, or the sketch's name)
  std::int64_t fid = 0;    // the polygon's
  AreaPattern pattern;
  // Per instance: its z (the run's final height under it); empty or NaN: unknown (`terraweave
  // area`, which has no terrain; an instance beyond the run's output window).
  std::vector<double> z;
};

// Layers `strokes` (LineString: class, polygon_fid, instance, shape, material, width_m) and
// `instances` (Point: class, polygon_fid, shape, type, material, rotation_deg (compass), scale)
// in `crs_wkt`; the points are Point Z when some result has z (NaN where unknown).
void write_area_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                           const std::vector<AreaResult>& results);

// x, y, z (empty where unknown), rotation_deg (compass bearing of the shape's axis), scale,
// type, material, class.
void write_instances_csv(const std::filesystem::path& path, const std::vector<AreaResult>& results);

// The same instances as a JSON array of objects with those keys (numbers as in the CSV; an
// unknown z is null).
void write_instances_json(const std::filesystem::path& path,
                          const std::vector<AreaResult>& results);

// The polygons (tinted, outlined), the avoided features (pale red) and the strokes in a colour
// per material, on white.
void write_area_preview(const std::filesystem::path& path, const std::vector<Polygon>& polygons,
                        const AvoidanceInputs& avoided, const std::vector<AreaResult>& results,
                        double resolution);

}  // namespace tw
