#include "terrain/height_ops.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "core/error.hpp"
#include "core/log.hpp"
#include "ribbon/junctions.hpp"
#include "terrain/detail/feature_index.hpp"
#include "terrain/detail/influence.hpp"
#include "terrain/detail/junctions.hpp"
#include "terrain/detail/precedence.hpp"
#include "terrain/detail/profiles.hpp"
#include "terrain/detail/structures.hpp"

namespace tw {

namespace {

using detail::Pin;

// Whether the feature's centreline, sampled every `step` metres, touches the grid.
bool reaches_grid(const TerrainFeature& f, const GridSpec& grid, double step) {
  const auto cumulative = cumulative_lengths(f.centerline);
  for (double s = 0.0; s <= cumulative.back(); s += step) {
    const Vec2 p = grid.world_to_pixel(point_at(f.centerline, cumulative, s));
    if (p.x >= 0.0 && p.y >= 0.0 && p.x <= grid.width && p.y <= grid.height) return true;
  }
  return false;
}

// Profile samples about every half pixel, spaced to divide the length exactly.
double profile_step(const GridSpec& grid, double length) {
  const double target = 0.5 * std::min(grid.pixel_width, grid.pixel_height);
  const double count = std::clamp(std::ceil(length / target), 1.0, 4.0e6);
  return length / count;
}

// Roads crossing through each other (X crossings, a road crossing itself) meet on one level
// platform: every road passing through is held at the mean of their graded levels wherever
// another crossing road's cut/fill reaches it. Two different levels there would make the
// blend of the surfaces steeper than either road (docs/terrain.md, "Junctions").
void add_crossing_pins(const TerrainPlan& plan, const std::vector<std::vector<double>>& profiles,
                       std::vector<std::vector<Pin>>& pins) {
  std::vector<Curve> roads;
  std::vector<std::size_t> feature_of;
  std::vector<CurveLevel> levels;
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    const TerrainFeature& f = plan.features[i];
    if (f.kind != FeatureKind::road || f.width <= 0.0 || f.structure != Structure::ground) continue;
    roads.push_back(f.centerline);
    feature_of.push_back(i);
    levels.push_back({f.structure, f.layer});
  }
  if (roads.empty()) return;
  std::vector<std::vector<double>> cumulative;
  for (const Curve& c : roads) cumulative.push_back(cumulative_lengths(c));
  // Below ~17 degrees the platform would grow without bound; such roads merge, not cross.
  constexpr double kMinSine = 0.3;
  for (const Junction& j : at_grade(find_junctions(roads, 0.0), levels)) {
    if (!j.crossing) continue;
    double sum = 0.0, reach = 0.0, sine = 1.0;
    std::vector<const JunctionMember*> passing;
    for (const JunctionMember& m : j.members) {
      if (m.at_endpoint) continue;  // an end here is pinned by the end contacts
      const std::size_t f = feature_of[m.curve];
      sum += detail::profile_at(profiles[f], plan.steps[f], m.arc_length);
      reach = std::max(reach, feature_reach(plan.features[f]));
      passing.push_back(&m);
    }
    if (passing.size() < 2) continue;
    const double h = 0.5 * std::min(plan.steps[feature_of[passing[0]->curve]], 1.0);
    for (std::size_t a = 0; a < passing.size(); ++a)
      for (std::size_t b = a + 1; b < passing.size(); ++b) {
        const Vec2 ta = tangent_at(roads[passing[a]->curve], cumulative[passing[a]->curve],
                                   passing[a]->arc_length, h);
        const Vec2 tb = tangent_at(roads[passing[b]->curve], cumulative[passing[b]->curve],
                                   passing[b]->arc_length, h);
        sine = std::min(sine, std::abs(cross(ta, tb)));
      }
    const double flat = reach / std::max(sine, kMinSine);
    for (const JunctionMember* m : passing)
      pins[feature_of[m->curve]].push_back({m->arc_length, sum / double(passing.size()), flat});
  }
}

// Roads meeting at their ends share one height there, so the blend of their surfaces is
// level: through roads (T-junctions) keep theirs, shared endpoints take the mean.
void pin_road_junctions(TerrainPlan& plan, std::vector<std::vector<double>>& profiles,
                        const std::vector<std::vector<detail::EndContact>>& contacts) {
  std::vector<std::vector<Pin>> pins(plan.features.size());
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    if (plan.features[i].kind != FeatureKind::road) continue;
    const double step = plan.steps[i];
    for (const bool at_start : {true, false}) {
      const double s = at_start ? 0.0 : double(profiles[i].size() - 1) * step;
      double through_sum = 0.0, shared_sum = 0.0;
      int through = 0, shared = 0;
      bool own_counted = false;
      for (const auto& c : contacts[i]) {
        if (c.at_start != at_start) continue;
        const auto& other = profiles[std::size_t(c.other)];
        const double h = std::clamp(
            other[std::min(other.size() - 1, std::size_t(std::llround(
                                                 c.other_s / plan.steps[std::size_t(c.other)])))],
            -1e30, 1e30);
        if (!c.other_end) {
          through_sum += h;
          ++through;
          continue;
        }
        // Sum in feature order so every road of the junction gets the same mean.
        if (!own_counted && std::size_t(c.other) > i) {
          shared_sum += profiles[i][at_start ? 0 : profiles[i].size() - 1];
          ++shared;
          own_counted = true;
        }
        shared_sum += h;
        ++shared;
      }
      if (through > 0) {
        pins[i].push_back({s, through_sum / through});
      } else if (shared > 0) {
        if (!own_counted) {
          shared_sum += profiles[i][at_start ? 0 : profiles[i].size() - 1];
          ++shared;
        }
        pins[i].push_back({s, shared_sum / shared});
      }
    }
  }
  add_crossing_pins(plan, profiles, pins);
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    const double period =
        plan.features[i].centerline.closed ? double(profiles[i].size() - 1) * plan.steps[i] : 0.0;
    detail::apply_pins(profiles[i], plan.steps[i], plan.features[i].road.max_grade, pins[i],
                       period);
  }
}

// A river continues into the river that starts at its mouth (that one's surface never starts
// above its feeder's), and a tributary's surface is eased down over its last stretch to the
// surface of the river it joins, so confluences have no step.
void join_rivers(TerrainPlan& plan, std::vector<std::vector<double>>& profiles,
                 const std::vector<std::vector<detail::EndContact>>& contacts) {
  const auto& fs = plan.features;
  auto surface_at = [&](std::size_t j, double s) {
    const auto& p = profiles[j];
    return p[std::min(p.size() - 1, std::size_t(std::llround(s / plan.steps[j])))];
  };
  for (std::size_t pass = 0; pass <= fs.size(); ++pass) {
    bool changed = false;
    for (std::size_t i = 0; i < fs.size(); ++i) {
      if (fs[i].kind != FeatureKind::river) continue;
      for (const auto& c : contacts[i]) {
        if (c.at_start || !c.other_end || c.other_s > 0.0) continue;
        auto& next = profiles[std::size_t(c.other)];
        if (next.front() > profiles[i].back()) {
          next.front() = profiles[i].back();
          const auto& r = fs[std::size_t(c.other)].river;
          next = detail::water_surface(next, plan.steps[std::size_t(c.other)], r.min_slope);
          changed = true;
        }
      }
    }
    if (!changed) break;
  }
  for (std::size_t i = 0; i < fs.size(); ++i) {
    if (fs[i].kind != FeatureKind::river) continue;
    for (const auto& c : contacts[i]) {
      if (c.at_start || c.other_end) continue;
      auto& p = profiles[i];
      const double excess = p.back() - surface_at(std::size_t(c.other), c.other_s);
      if (excess <= 0.0) continue;
      const auto& r = fs[i].river;
      const double ramp = fs[i].width + r.bank_width + r.falloff;
      const double total = double(p.size() - 1) * plan.steps[i];
      // Subtracting a non-decreasing ramp keeps the surface non-increasing.
      for (std::size_t k = 0; k < p.size(); ++k) {
        const double s = double(k) * plan.steps[i];
        p[k] -= excess * std::clamp((s - (total - ramp)) / ramp, 0.0, 1.0);
      }
    }
  }
}

// A river crossing itself (a loop in the line, docs/junctions.md) meets itself at one water
// level, as two rivers meet at a confluence: the level of its later (downstream) pass. The
// stretch from the first pass to the second is held at or below it, and the drop before the
// first pass is eased in over width + bank + falloff metres, so the surface never rises
// downstream and has no step.
void level_river_self_crossings(const TerrainPlan& plan,
                                std::vector<std::vector<double>>& profiles) {
  std::vector<Curve> rivers;
  std::vector<std::size_t> feature_of;
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    if (plan.features[i].kind != FeatureKind::river || plan.features[i].width <= 0.0) continue;
    rivers.push_back(plan.features[i].centerline);
    feature_of.push_back(i);
  }
  if (rivers.empty()) return;
  for (const Junction& j : find_junctions(rivers, 0.0)) {
    for (std::size_t c = 0; c < rivers.size(); ++c) {
      double first = std::numeric_limits<double>::infinity(), last = -first;
      int passes = 0;
      for (const JunctionMember& m : j.members) {
        if (m.curve != c) continue;
        first = std::min(first, m.arc_length);
        last = std::max(last, m.arc_length);
        ++passes;
      }
      if (passes < 2) continue;
      const std::size_t f = feature_of[c];
      auto& p = profiles[f];
      const double step = plan.steps[f];
      const double level = detail::profile_at(p, step, last);
      const double excess = detail::profile_at(p, step, first) - level;
      if (!(excess > 0.0)) continue;
      const auto& r = plan.features[f].river;
      const double ramp = std::max(plan.features[f].width + r.bank_width + r.falloff, step);
      for (std::size_t k = 0; k < p.size(); ++k) {
        const double s = double(k) * step;
        if (s < first) {
          p[k] -= excess * std::clamp((s - (first - ramp)) / ramp, 0.0, 1.0);
        } else if (s <= last) {
          p[k] = std::min(p[k], level);
        }
      }
    }
  }
}

// Bed = water surface - depth. A river whose source joins no other river starts at a spring:
// its depth eases in from 0 over width + bank + falloff metres instead of a round pit.
void carve_river_beds(TerrainPlan& plan, std::vector<std::vector<double>>& profiles,
                      const std::vector<std::vector<detail::EndContact>>& contacts) {
  const auto& fs = plan.features;
  std::vector<char> fed(fs.size(), 0);
  for (std::size_t i = 0; i < fs.size(); ++i)
    for (const auto& c : contacts[i]) {
      if (c.at_start) fed[i] = 1;  // starts on another river
      if (!c.at_start && c.other_end && c.other_s == 0.0) fed[std::size_t(c.other)] = 1;
    }
  for (std::size_t i = 0; i < fs.size(); ++i) {
    if (fs[i].kind != FeatureKind::river) continue;
    const auto& r = fs[i].river;
    const double taper = fs[i].width + r.bank_width + r.falloff;
    for (std::size_t k = 0; k < profiles[i].size(); ++k) {
      const double s = double(k) * plan.steps[i];
      profiles[i][k] -= r.depth * (fed[i] ? 1.0 : detail::smoothstep01(s / taper));
    }
  }
}

// The feature's bound below (cut) and above (fill) the terrain, metres (infinite: none).
std::pair<double, double> earthwork_bounds(const TerrainFeature& f) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  switch (f.kind) {
    case FeatureKind::road:
      return {f.road.max_cut.value_or(kNone), f.road.max_fill.value_or(kNone)};
    case FeatureKind::river:
      return {max_carve(f.river), kNone};
    case FeatureKind::ridge:
      break;
  }
  return {kNone, kNone};
}

// Holds each profile within its bounds of the terrain along the centreline (the last word,
// after junctions: a bound breaks the grade or the never-rising surface locally rather than
// cut a canyon), records where, and measures the largest cut and fill.
void bound_earthwork(TerrainPlan& plan, std::vector<std::vector<double>>& profiles,
                     const std::vector<std::vector<double>>& terrains) {
  plan.earthwork.assign(plan.features.size(), FeatureEarthwork{});
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    const TerrainFeature& f = plan.features[i];
    FeatureEarthwork& e = plan.earthwork[i];
    if (f.kind == FeatureKind::ridge) {
      if (f.width > 0.0) e.max_fill = std::max(0.0, f.ridge.height);
      continue;
    }
    if (terrains[i].empty()) continue;  // left out: nothing applied
    const auto [cut_bound, fill_bound] = earthwork_bounds(f);
    const auto cumulative = cumulative_lengths(f.centerline);
    auto& p = profiles[i];
    const double step = plan.steps[i];
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double t = terrains[i][k];
      const double cut = t - p[k];
      ProfileLimit* limit = nullptr;
      double excess = 0.0;
      if (cut > cut_bound) {
        limit = &e.cut_limited, excess = cut - cut_bound, p[k] = t - cut_bound;
      } else if (-cut > fill_bound) {
        limit = &e.fill_limited, excess = -cut - fill_bound, p[k] = t + fill_bound;
      }
      if (limit) {
        limit->length += step;
        if (excess > limit->excess) {
          limit->excess = excess;
          limit->along = double(k) * step;
          limit->at = point_at(f.centerline, cumulative, limit->along);
        }
      }
      e.max_cut = std::max(e.max_cut, t - p[k]);
      e.max_fill = std::max(e.max_fill, p[k] - t);
    }
  }
}

}  // namespace

TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params) {
  Warnings warnings;  // logged as they are raised
  return plan_terrain(height, grid, features, params, warnings);
}

TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params,
                         Warnings& warnings) {
  if (height.width != grid.width || height.height != grid.height)
    fail("shape_terrain: height raster is {} x {}, the grid is {} x {}", height.width,
         height.height, grid.width, grid.height);
  const auto source = in_memory_heightfield(height, grid);
  HeightSampler heights(*source);
  return plan_terrain(heights, features, params, warnings);
}

TerrainPlan plan_terrain(HeightSampler& heights, const std::vector<TerrainFeature>& features,
                         const TerrainParams& params, Warnings& warnings) {
  return plan_terrain(heights.grid(), sample_heights_along(heights), features, params, warnings);
}

HeightsAlong sample_heights_along(HeightSampler& heights) {
  return [&heights](const Curve& centerline, double step) {
    return detail::terrain_along(heights, centerline, step);
  };
}

TerrainPlan plan_terrain(const GridSpec& grid, const HeightsAlong& heights_along,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params,
                         Warnings& warnings) {
  TerrainPlan plan;
  plan.params = params;
  const auto ranks = detail::precedence_ranks(params);
  for (const auto& f : features) {
    validate_feature(f);
    if (ranks[std::size_t(f.kind)] < 0)
      fail("{} feature FID {}: its kind is missing from the terrain precedence", to_string(f.kind),
           f.fid);
  }
  plan.input_index.resize(features.size());
  std::iota(plan.input_index.begin(), plan.input_index.end(), std::size_t(0));
  std::stable_sort(plan.input_index.begin(), plan.input_index.end(), [&](auto a, auto b) {
    return ranks[std::size_t(features[a].kind)] < ranks[std::size_t(features[b].kind)];
  });
  for (const std::size_t i : plan.input_index) {
    TerrainFeature copy = features[i];
    copy.centerline = without_duplicates(features[i].centerline);
    plan.features.push_back(std::move(copy));
  }

  std::vector<std::vector<double>> profiles(plan.features.size());
  std::vector<std::vector<double>> terrains(plan.features.size());
  std::vector<char> over_nodata(plan.features.size(), 0);
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    const auto& f = plan.features[i];
    const double step = profile_step(grid, arc_length(f.centerline));
    plan.steps.push_back(step);
    if (f.kind == FeatureKind::ridge) {
      profiles[i] = {0.0};
      continue;
    }
    auto terrain = heights_along(f.centerline, step);
    if (terrain.empty()) {
      // Off this grid altogether (a close-up region, a tile) is expected; over nodata is not.
      if (reaches_grid(f, grid, step)) {
        warnings.add("over_nodata", f.subject.empty() ? std::string(to_string(f.kind)) : f.subject,
                     f.fid, "lies entirely over nodata; left out");
      } else {
        logger().debug("{} feature FID {} lies outside the grid", to_string(f.kind), f.fid);
      }
      over_nodata[i] = 1;
      plan.features[i].width = 0.0;  // marks "nothing to apply", and no crossing pins
      profiles[i] = {0.0};
      continue;
    }
    if (f.kind == FeatureKind::road && f.centerline.closed) {
      profiles[i] = detail::limit_grade_closed(
          detail::moving_average_closed(terrain, step, f.road.smoothing), step, f.road.max_grade);
    } else if (f.kind == FeatureKind::road) {
      profiles[i] = detail::limit_grade(detail::moving_average(terrain, step, f.road.smoothing),
                                        step, f.road.max_grade);
    } else {
      profiles[i] = detail::water_surface(terrain, step, f.river.min_slope);
    }
    terrains[i] = std::move(terrain);
  }
  auto contacts =
      detail::find_end_contacts(plan.features, 0.5 * std::max(grid.pixel_width, grid.pixel_height));
  // A feature left out (over nodata, off a close-up grid) has no profile for others to meet.
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (over_nodata[i]) contacts[i].clear();
    std::erase_if(contacts[i], [&](const detail::EndContact& c) {
      return over_nodata[std::size_t(c.other)] != 0;
    });
  }
  // Roads are graded without their bridges and tunnels, whose decks then follow them.
  const auto contacts_with_structures = contacts;
  detail::drop_road_structure_contacts(plan.features, contacts);
  pin_road_junctions(plan, profiles, contacts);
  join_rivers(plan, profiles, contacts);
  level_river_self_crossings(plan, profiles);

  carve_river_beds(plan, profiles, contacts);
  detail::lay_decks(plan.features, plan.steps, contacts_with_structures, profiles);
  bound_earthwork(plan, profiles, terrains);

  for (std::size_t i = 0; i < plan.features.size(); ++i)
    plan.profiles.emplace_back(profiles[i].begin(), profiles[i].end());
  return plan;
}

namespace {

// Per pixel and kind: the weighted mean of the features' values and the strongest weight.
struct KindAccumulator {
  double weight_sum = 0.0;
  double value_sum = 0.0;
  double weight_max = 0.0;
  // The tightest earthwork bounds of the features holding the pixel (metres of cut, fill).
  double cut_bound = std::numeric_limits<double>::infinity();
  double fill_bound = std::numeric_limits<double>::infinity();
};

}  // namespace

void apply_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const TerrainPlan& plan) {
  if (window.col0 < 0 || window.row0 < 0 || window.col_end() > grid.width ||
      window.row_end() > grid.height)
    fail("shape_terrain: window ({}, {}, {} x {}) is outside the {} x {} grid", window.col0,
         window.row0, window.width, window.height, grid.width, grid.height);
  const bool whole_grid = height.width == grid.width && height.height == grid.height;
  if (!whole_grid && (height.width != window.width || height.height != window.height))
    fail("shape_terrain: height raster is {} x {}, neither the grid ({} x {}) nor the window",
         height.width, height.height, grid.width, grid.height);
  // Where pixel (0, 0) of `height` lies on the grid.
  const int height_col0 = whole_grid ? 0 : window.col0;
  const int height_row0 = whole_grid ? 0 : window.row0;
  const double pixel = std::min(grid.pixel_width, grid.pixel_height);
  std::vector<const Curve*> curves;
  std::vector<double> reach;
  for (const auto& f : plan.features) {
    curves.push_back(&f.centerline);
    // A bridge or tunnel leaves the ground under it untouched. The weight is a pixel's
    // average: it reaches half a pixel further than the feature.
    const bool shapes_ground = f.width > 0.0 && f.structure == Structure::ground;
    reach.push_back(shapes_ground ? feature_reach(f) + 0.5 * pixel : -1.0);
  }
  const detail::FeatureIndex index(grid, window, curves, reach);
  const auto ranks = detail::precedence_ranks(plan.params);
  const std::size_t kinds = plan.params.precedence.size();

  tbb::parallel_for(tbb::blocked_range<int>(0, index.tile_count()), [&](const auto& range) {
    std::vector<detail::NearestSample> samples;
    std::vector<KindAccumulator> acc;
    for (int t = range.begin(); t != range.end(); ++t) {
      if (index.tile_is_empty(t)) continue;
      const Window tile = index.tile(t);
      const std::size_t n = std::size_t(tile.width) * tile.height;
      acc.assign(n * kinds, KindAccumulator{});
      index.for_each_feature(t, samples, [&](int fi, const std::vector<detail::NearestSample>& s) {
        const auto& f = plan.features[std::size_t(fi)];
        const auto& profile = plan.profiles[std::size_t(fi)];
        const double step = plan.steps[std::size_t(fi)];
        const std::size_t rank = std::size_t(ranks[std::size_t(f.kind)]);
        const auto [cut_bound, fill_bound] = earthwork_bounds(f);
        for (std::size_t k = 0; k < n; ++k) {
          if (!std::isfinite(s[k].distance)) continue;
          const double w = detail::cell_height_weight(f, s[k].distance, pixel);
          if (w <= 0.0) continue;
          double value = f.ridge.height;
          if (f.kind != FeatureKind::ridge) value = detail::profile_at(profile, step, s[k].along);
          auto& a = acc[k * kinds + rank];
          a.weight_sum += w;
          a.value_sum += w * value;
          a.weight_max = std::max(a.weight_max, w);
          a.cut_bound = std::min(a.cut_bound, cut_bound);
          a.fill_bound = std::min(a.fill_bound, fill_bound);
        }
      });
      for (int r = 0; r < tile.height; ++r)
        for (int c = 0; c < tile.width; ++c) {
          float& cell = height.at(tile.col0 - height_col0 + c, tile.row0 - height_row0 + r);
          if (std::isnan(cell)) continue;  // nodata is never read nor written
          double h = cell;
          const std::size_t k = std::size_t(r) * tile.width + c;
          for (std::size_t rank = 0; rank < kinds; ++rank) {
            const auto& a = acc[k * kinds + rank];
            if (a.weight_max <= 0.0) continue;
            const double mean = a.value_sum / a.weight_sum;
            double target = mean;
            // A bank on a hillside is held to the same bounds as the centreline.
            switch (plan.params.precedence[rank]) {
              case FeatureKind::road:
                target = std::clamp(mean, h - a.cut_bound, h + a.fill_bound);
                break;
              case FeatureKind::river:
                target = std::max(std::min(h, mean), h - a.cut_bound);
                break;  // rivers only carve
              case FeatureKind::ridge:
                target = h + mean;
                break;
            }
            h += (target - h) * a.weight_max;
          }
          cell = float(h);
        }
    }
  });
}

void shape_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const std::vector<TerrainFeature>& features, const TerrainParams& params) {
  apply_terrain(height, grid, window, plan_terrain(height, grid, features, params));
}

void shape_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const std::vector<TerrainFeature>& features, const TerrainParams& params,
                   Warnings& warnings) {
  apply_terrain(height, grid, window, plan_terrain(height, grid, features, params, warnings));
}

void shape_heightfield(Heightfield& heightfield, const std::vector<TerrainFeature>& features,
                       const TerrainParams& params) {
  shape_terrain(heightfield.height, heightfield.grid, Window::whole(heightfield.grid), features,
                params);
}

}  // namespace tw
