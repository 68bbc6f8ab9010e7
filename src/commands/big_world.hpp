#pragma once
// A generated world for scaling benchmarks (bench/bigworld.sh, docs/performance.md "Memory"):
// a generated heightfield (no DEM file, however large the world) and a GeoPackage of roads and
// rivers with the demo's density of features per km^2: a road network on a jittered grid with
// curved segments meeting at shared nodes, and rivers that follow the generated terrain's flow
// downhill. Writes <dir>/world.gpkg and the pipelines <dir>/world.yaml (tiled) and
// <dir>/world_untiled.yaml (one window).
#include <cstdint>
#include <filesystem>

namespace tw {

struct BigWorldOptions {
  int size = 8192;                    // cells per side
  double pixel_size = 1.5;            // metres: 32768 cells make a 49 km world
  std::uint64_t seed = 1;             // terrain (the pipeline's seed) and network
  double relief = 150.0;              // metres
  double road_spacing = 3000.0;       // metres between the road grid's nodes
  double river_km_per_km2 = 0.35;     // river length per area (the demo: about 0.6)
  double max_river_length = 12000.0;  // metres
  int tile_size = 2048;               // output.tiles of world.yaml
  int tile_overlap = 64;
  std::filesystem::path dir;
};

struct BigWorldSummary {
  int roads = 0;
  int rivers = 0;
  double road_km = 0.0;
  double river_km = 0.0;
  double area_km2 = 0.0;
};

BigWorldSummary write_big_world(const BigWorldOptions& options);

}  // namespace tw
