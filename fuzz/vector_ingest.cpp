// libFuzzer target: vector ingest of a small GeoJSON (or whatever GDAL recognizes in the bytes)
// written to /vsimem/, read with read_line_features and read_polygon_features over a small
// generated heightfield. What comes back must be finite, clipped to the grid and well formed.
#include <cpl_vsi.h>

#include <cstddef>
#include <cstdint>

#include "core/warnings.hpp"
#include "fuzz_support.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "offline_gdal.hpp"

namespace {

constexpr const char* kPath = "/vsimem/fuzz.geojson";

const tw::Heightfield& grid() {
  static const tw::Heightfield heightfield = [] {
    tw::GeneratedTerrain params;
    params.width = 32;
    params.height = 32;
    params.pixel_size = 10.0;  // x 500000..500320, y 4999680..5000000 in UTM 31N
    params.feature_size = 160.0;
    return tw::generate_heightfield(params);
  }();
  return heightfield;
}

// Inside the grid's extent grown by `halo` metres (lines are clipped to the extent plus half
// their width and the class's clip margin), allowing for the rounding of the clipper.
void expect_on_grid(const tw::Vec2& p, double halo = 0.0) {
  const tw::GridSpec& g = grid().grid;
  const double slack = 1e-6 * g.pixel_width + halo;
  tw::fuzz::expect_finite(p.x, "vertex x");
  tw::fuzz::expect_finite(p.y, "vertex y");
  if (p.x < g.origin_x - slack || p.x > g.origin_x + g.width * g.pixel_width + slack ||
      p.y > g.origin_y + slack || p.y < g.origin_y - g.height * g.pixel_height - slack)
    tw::fuzz::broken_promise("a vertex outside the grid it was clipped to");
}

void read_lines() {
  tw::LineClassSpec spec;
  spec.name = "fuzz";
  spec.source.path = kPath;
  spec.width_attribute = "width";
  spec.default_width = 4.0;
  tw::Warnings warnings;  // repairs are expected answers, like errors
  for (const tw::LineFeature& line : tw::read_line_features(spec, grid(), warnings)) {
    if (line.points.size() < 2) tw::fuzz::broken_promise("a line with fewer than 2 points");
    if (!(std::isfinite(line.width) && line.width > 0.0))
      tw::fuzz::broken_promise("a line without a positive width");
    for (const tw::Vec2& p : line.points) expect_on_grid(p, 0.5 * line.width + spec.clip_margin);
  }
}

void read_polygons() {
  const tw::VectorSource source{kPath, "", ""};
  tw::Warnings warnings;
  for (const tw::PolygonFeature& polygon :
       tw::read_polygon_features(source, grid(), "fuzz", warnings)) {
    if (polygon.rings.empty()) tw::fuzz::broken_promise("a polygon without rings");
    for (const auto& ring : polygon.rings) {
      if (ring.size() < 3) tw::fuzz::broken_promise("a ring with fewer than 3 points");
      for (const tw::Vec2& p : ring) expect_on_grid(p);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  tw::fuzz::start_offline_gdal();
  (void)grid();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  VSILFILE* file =
      VSIFileFromMemBuffer(kPath, const_cast<GByte*>(data), static_cast<vsi_l_offset>(size),
                           /*bTakeOwnership=*/FALSE);
  if (file == nullptr) return 0;
  VSIFCloseL(file);
  try {
    read_lines();
  } catch (const tw::Error&) {
    // Refused with a message naming the file and the FID: expected for bad input.
  }
  try {
    read_polygons();
  } catch (const tw::Error&) {
  }
  VSIUnlink(kPath);
  return 0;
}
