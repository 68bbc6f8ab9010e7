#include "commands/big_world.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/geopackage.hpp"
#include "geo/heightfield_source.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using Line = std::vector<Vec2>;

constexpr double kOriginX = 500000.0, kOriginY = 5000000.0;
constexpr const char* kCrs = "EPSG:32631";

// Uniform in [0, 1) from 53 random bits: the same numbers on every standard library.
double uniform(std::mt19937_64& random) {
  return double(random() >> 11) * 0x1.0p-53;
}

double length_of(const Line& line) {
  double sum = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) sum += length(line[i] - line[i - 1]);
  return sum;
}

// Nodes every `spacing` metres, jittered by up to a sixth of it; segments between neighbours
// bow sideways (zero at the nodes, which they share: the network's junctions).
std::vector<Line> road_grid(double side, double spacing, std::mt19937_64& random) {
  const int n = std::max(1, int(std::floor(side / spacing)));
  const double margin = 0.5 * (side - (n - 1) * spacing);
  std::vector<Vec2> nodes(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double jx = (uniform(random) - 0.5) * spacing / 3.0;
      const double jy = (uniform(random) - 0.5) * spacing / 3.0;
      nodes[std::size_t(j) * n + i] = {kOriginX + margin + i * spacing + jx,
                                       kOriginY - margin - j * spacing - jy};
    }
  std::vector<Line> roads;
  const auto segment = [&](Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    const Vec2 normal = Vec2{-d.y, d.x} * (1.0 / length(d));
    const double bow = (uniform(random) - 0.5) * 0.25 * length(d);
    const double wiggle = (uniform(random) - 0.5) * 0.04 * length(d);
    const int steps = std::max(2, int(length(d) / 25.0));
    Line line;
    for (int k = 0; k <= steps; ++k) {
      const double t = double(k) / steps;
      const double offset =
          bow * std::sin(std::numbers::pi * t) + wiggle * std::sin(3.0 * std::numbers::pi * t);
      line.push_back(a + d * t + normal * offset);
    }
    roads.push_back(std::move(line));
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 a = nodes[std::size_t(j) * n + i];
      if (i + 1 < n) segment(a, nodes[std::size_t(j) * n + i + 1]);
      if (j + 1 < n) segment(a, nodes[std::size_t(j + 1) * n + i]);
    }
  return roads;
}

// From a random source, steps of 30 m towards the lowest of the headings within 60 degrees of
// the current one (momentum carries it through pits), until the world's edge or the length.
std::vector<Line> rivers_following_flow(const HeightfieldSource& terrain, double target_length,
                                        double max_length, std::mt19937_64& random) {
  const GridSpec& g = terrain.grid();
  const double side = g.width * g.pixel_width;
  const auto height_at = [&](Vec2 p) -> double {
    const Vec2 px = g.world_to_pixel(p);
    const int c = int(std::floor(px.x)), r = int(std::floor(px.y));
    if (c < 0 || r < 0 || c >= g.width || r >= g.height) return -1e9;  // the edge drains
    return terrain.read({c, r, 1, 1}).pixels[0];
  };
  constexpr double kStep = 30.0;
  std::vector<Line> rivers;
  double total = 0.0;
  while (total < target_length) {
    Vec2 p{kOriginX + (0.05 + 0.9 * uniform(random)) * side,
           kOriginY - (0.05 + 0.9 * uniform(random)) * side};
    double heading = 2.0 * std::numbers::pi * uniform(random);
    const double wanted = max_length * (0.4 + 0.6 * uniform(random));
    Line line{p};
    double along = 0.0;
    while (along < wanted) {
      double best = 1e300, best_heading = heading;
      for (int k = -4; k <= 4; ++k) {
        const double h = heading + k * (std::numbers::pi / 12.0);
        const double z = height_at(p + Vec2{std::cos(h), std::sin(h)} * kStep);
        if (z < best) best = z, best_heading = h;
      }
      heading = 0.5 * heading + 0.5 * best_heading;  // smooth turns
      p = p + Vec2{std::cos(heading), std::sin(heading)} * kStep;
      line.push_back(p);
      along += kStep;
      if (best <= -1e9) break;  // left the world
    }
    total += along;
    rivers.push_back(std::move(line));
  }
  return rivers;
}

void write_layer(GeoPackageWriter& gpkg, const char* name, const std::vector<Line>& lines,
                 double width) {
  OGRLayer* layer = &gpkg.create_layer(name, wkbLineString);
  gpkg.add_fields(*layer, {{"width", OFTReal}});
  if (layer->StartTransaction() != OGRERR_NONE) fail("world.gpkg: cannot create layer {}", name);
  for (const Line& line : lines) {
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("width", width);
    OGRLineString geometry;
    for (const Vec2 p : line) geometry.addPoint(p.x, p.y);
    feature.SetGeometry(&geometry);
    if (layer->CreateFeature(&feature) != OGRERR_NONE) fail("world.gpkg: cannot write {}", name);
  }
  if (layer->CommitTransaction() != OGRERR_NONE) fail("world.gpkg: cannot write {}", name);
}

void write_pipeline(const fs::path& path, const BigWorldOptions& o, bool tiled) {
  std::ofstream out(path);
  out << "# A generated world of " << o.size << "^2 cells (terraweave make-world; docs/"
      << "performance.md, \"Memory\"). Paths are relative to this file.\n"
      << "version: 1\nseed: " << o.seed << "\n"
      << "generate: { width: " << o.size << ", height: " << o.size
      << ", pixel_size: " << o.pixel_size << ", relief: " << o.relief << ", crs: \"" << kCrs
      << "\", origin: [" << fmt::format("{}, {}", kOriginX, kOriginY) << "] }\n"
      << "output: { dir: out" << (tiled ? "" : "_untiled")
      << ", exr: true, geotiff: false, preview: false";
  if (tiled) out << ", tiles: { size: " << o.tile_size << ", overlap: " << o.tile_overlap << " }";
  out << " }\nprecedence: [rivers, roads]\nfeatures:\n"
      << "  rivers:\n    source: world.gpkg\n    layer: rivers\n    kind: river\n"
      << "    width_attribute: width\n    width: 10\n"
      << "    profile: { depth: 2.5, bank_width: 6, falloff: 20 }\n"
      << "  roads:\n    source: world.gpkg\n    layer: roads\n    kind: road\n"
      << "    width_attribute: width\n    width: 6\n"
      << "    profile: { max_grade: 0.08, shoulder_width: 3, falloff: 15, smoothing: 60 }\n";
  out.close();
  if (!out) fail("cannot write {}", path.string());
}

}  // namespace

BigWorldSummary write_big_world(const BigWorldOptions& o) {
  if (o.size < 64) fail("make-world: size must be at least 64 cells, got {}", o.size);
  if (!(o.pixel_size > 0.0)) fail("make-world: pixel size must be positive, got {}", o.pixel_size);
  fs::create_directories(o.dir);
  GeneratedTerrain params;
  params.width = params.height = o.size;
  params.pixel_size = o.pixel_size;
  params.seed = o.seed;
  params.relief = o.relief;
  params.crs = kCrs;
  params.origin_x = kOriginX;
  params.origin_y = kOriginY;
  const auto terrain = open_generated_heightfield(params);  // the pipeline's terrain

  BigWorldSummary summary;
  const double side = o.size * o.pixel_size;
  summary.area_km2 = side * side * 1e-6;
  std::mt19937_64 random(o.seed ^ 0x9e3779b97f4a7c15ULL);
  const std::vector<Line> roads = road_grid(side, o.road_spacing, random);
  const std::vector<Line> rivers = rivers_following_flow(
      *terrain, o.river_km_per_km2 * summary.area_km2 * 1000.0, o.max_river_length, random);
  for (const Line& l : roads) summary.road_km += length_of(l) * 1e-3;
  for (const Line& l : rivers) summary.river_km += length_of(l) * 1e-3;
  summary.roads = int(roads.size());
  summary.rivers = int(rivers.size());

  const fs::path gpkg_path = o.dir / "world.gpkg";
  fs::remove(gpkg_path);
  {
    GeoPackageWriter gpkg = create_geopackage(gpkg_path, kCrs);
    write_layer(gpkg, "rivers", rivers, 10.0);
    write_layer(gpkg, "roads", roads, 6.0);
  }
  write_pipeline(o.dir / "world.yaml", o, true);
  write_pipeline(o.dir / "world_untiled.yaml", o, false);
  logger().info("{}: {} roads ({:.0f} km), {} rivers ({:.0f} km) over {:.0f} km^2", o.dir.string(),
                summary.roads, summary.road_km, summary.rivers, summary.river_km, summary.area_km2);
  return summary;
}

}  // namespace tw
