// render_tile (pipeline/plan.hpp): every layer of one window, as per-pixel functions of the
// plan, so any tiling gives the same bits as an untiled render.
#include <algorithm>

#include "core/error.hpp"
#include "layers/layer_set.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/footprint.hpp"
#include "terrain/splat.hpp"

namespace tw {

namespace {

// The part of the global terrain plan whose features can touch the window (in plan order, so
// per-pixel sums run in the same order as on the whole grid).
TerrainPlan terrain_part(const TerrainPlan& plan, const std::vector<std::size_t>& inputs_met) {
  TerrainPlan part;
  part.params = plan.params;
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    if (!std::binary_search(inputs_met.begin(), inputs_met.end(), plan.input_index[i])) continue;
    part.features.push_back(plan.features[i]);
    part.profiles.push_back(plan.profiles[i]);
    part.steps.push_back(plan.steps[i]);
    part.input_index.push_back(plan.input_index[i]);
    part.earthwork.push_back(plan.earthwork[i]);
  }
  return part;
}

Layer avoidance_layer(AvoidanceMap map) {
  Raster<float> forbidden(map.forbidden.width, map.forbidden.height);
  std::transform(map.forbidden.pixels.begin(), map.forbidden.pixels.end(), forbidden.pixels.begin(),
                 [](std::uint8_t v) { return v ? 1.0f : 0.0f; });
  Layer layer;
  layer.name = "avoidance";
  layer.channels = {"forbidden", "distance"};
  layer.bands.push_back(std::move(forbidden));
  layer.bands.push_back(std::move(map.distance));
  return layer;
}

// Existing features, every ribbon's footprint and fold-overs, and the junction discs, with the
// distance capped so the halo it reads is bounded.
AvoidanceMap tile_avoidance(const WorldPlan& plan, const Window& window) {
  const double cap = plan.render.avoidance_max_distance;
  const int halo = avoidance_halo_pixels(plan);
  std::vector<const Ribbon*> all;
  for (const auto& class_ribbons : plan.ribbons)
    for (const Ribbon& r : class_ribbons) all.push_back(&r);
  AvoidanceInputs inputs;
  inputs.polygons = plan.existing.polygons;
  inputs.lines = plan.existing.lines;
  inputs.line_widths = plan.existing.line_widths;
  inputs.junction_discs = plan.junction_discs;
  inputs.include_foldovers = true;
  for (const std::size_t r : items_meeting(plan.ribbon_index, grow_window(window, halo, plan.grid)))
    inputs.ribbons.push_back(all[r]);
  return build_avoidance_map(inputs, plan.grid, window, cap);
}

}  // namespace

int avoidance_halo_pixels(const WorldPlan& plan) {
  const double pixel = std::min(plan.grid.pixel_width, plan.grid.pixel_height);
  return int(std::min(std::ceil(plan.render.avoidance_max_distance / pixel) + 1.0, 1e9));
}

LayerSet render_tile(const WorldPlan& plan, const TileSpec& tile) {
  const Window& window = tile.halo_window;
  if (window.width <= 0 || window.height <= 0 ||
      intersect(window, Window::whole(plan.grid)) != window)
    fail("render_tile: tile {} window ({}, {}, {} x {}) is not inside the {} x {} grid", tile.index,
         window.col0, window.row0, window.width, window.height, plan.grid.width, plan.grid.height);
  Raster<float> height = read_height_window(plan.heights, plan.grid, window);

  const std::vector<std::size_t> met = items_meeting(plan.feature_index, window);
  apply_terrain(height, plan.grid, window, terrain_part(plan.terrain, met));
  std::vector<TerrainFeature> features;
  for (const std::size_t f : met) features.push_back(plan.terrain_features[f]);
  SplatLayers splat = compute_splat(plan.grid, window, features, plan.terrain_params, height);
  for (std::size_t m = splat.materials.size(); m < plan.splat_materials.size(); ++m) {
    splat.materials.push_back(plan.splat_materials[m]);
    splat.weights.emplace_back(window.width, window.height, 0.0f);
  }
  // Every method that writes into the layers, in the methods' order.
  for (const MethodPlan& entry : plan.methods)
    if (entry.method->renders()) entry.method->render(plan, entry, window, height, splat);

  LayerSet layers;
  layers.grid = window_grid(plan.grid, window);
  layers.crs_wkt = plan.crs_wkt;
  layers.nodata = plan.nodata;
  layers.layers.push_back(height_layer(std::move(height)));
  layers.layers.push_back(splat_layer(std::move(splat)));
  layers.layers.push_back(avoidance_layer(tile_avoidance(plan, window)));
  // Splat and avoidance are NaN where the height is nodata: here, the one place every run
  // (untiled, tiled, render-tile) renders, so no writer decides it on its own.
  blank_where_height_is_nodata(layers);
  return layers;
}

}  // namespace tw
