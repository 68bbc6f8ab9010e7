#include <algorithm>
#include <bit>
#include <cmath>
#include <mutex>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "core/grid_limits.hpp"
#include "geo/detail/gdal_support.hpp"
#include "geo/detail/generated_source.hpp"
#include "geo/detail/gradient_noise.hpp"
#include "geo/heightfield.hpp"
#include "geo/heightfield_source.hpp"

namespace tw {

namespace {

// The parameters other than the CRS checked (tw::Error naming the first bad one).
void check_generated_params(const GeneratedTerrain& params, const std::string& name) {
  if (params.width <= 0 || params.height <= 0) {
    fail("{}: size must be positive, got {} x {}", name, params.width, params.height);
  }
  require_grid_size(params.width, params.height, name);
  if (!(std::isfinite(params.pixel_size) && params.pixel_size > 0.0)) {
    fail("{}: pixel_size must be a positive number of metres, got {}", name, params.pixel_size);
  }
  if (!(std::isfinite(params.feature_size) && params.feature_size > 0.0)) {
    fail("{}: feature_size must be a positive number of metres, got {}", name, params.feature_size);
  }
  if (!(std::isfinite(params.origin_x) && std::isfinite(params.origin_y))) {
    fail("{}: origin ({}, {}) is not a usable coordinate", name, params.origin_x, params.origin_y);
  }
  // Noise is indexed by world pixel in 64-bit integers: the origin must lie within 1e15 pixels.
  if (std::abs(params.origin_x / params.pixel_size) > 1e15 ||
      std::abs(params.origin_y / params.pixel_size) > 1e15) {
    fail(
        "{}: pixel_size {} m is too small for origin ({}, {}): the origin lies over 1e15 pixels "
        "from 0",
        name, params.pixel_size, params.origin_x, params.origin_y);
  }
  if (!(std::isfinite(params.relief) && params.relief >= 0.0 &&
        params.relief <= kMaxGeneratedRelief)) {
    fail("{}: relief must be in [0, {}] metres, got {}", name, kMaxGeneratedRelief, params.relief);
  }
}

// The parameters checked (tw::Error naming the first bad one) and the CRS as WKT.
std::string checked_crs_wkt(const GeneratedTerrain& params, const std::string& name) {
  check_generated_params(params, name);
  detail::ensure_gdal_registered();
  detail::QuietGdalErrors quiet;
  OGRSpatialReference srs;
  if (!detail::import_traditional_srs(srs, params.crs)) {
    fail("{}: unknown CRS '{}'", name, params.crs);
  }
  if (!srs.IsProjected() || std::abs(srs.GetLinearUnits() - 1.0) > 1e-12) {
    fail("{}: CRS '{}' is not a projected CRS in metres", name, params.crs);
  }
  return detail::to_wkt(srs);
}

// Cells (col0 .. col0 + width, row0 .. row0 + height) of the generated world.
Raster<float> generate_cells(const GeneratedTerrain& params, int col0, int row0, int width,
                             int height) {
  Raster<float> out(width, height);
  // Noise is indexed by world pixel (origin / pixel size + pixel), and the largest hills span
  // feature_size metres (a power-of-two number of pixels, so each octave's lattice nests in the
  // previous one's): a tile generated on its own equals the same window of a larger world.
  const std::int64_t largest_cell = std::max<std::int64_t>(
      2, std::int64_t(std::bit_floor(std::uint64_t(params.feature_size / params.pixel_size))));
  const std::int64_t world_col0 = std::llround(params.origin_x / params.pixel_size) + col0;
  const std::int64_t world_row0 = std::llround(-params.origin_y / params.pixel_size) + row0;
  const double metres_per_unit = params.relief / (2.0 * double(detail::kNoiseOne));
  // Rows are independent: any split over threads gives the same bytes.
  tbb::parallel_for(0, height, [&](int row) {
    std::vector<std::int64_t> noise(static_cast<std::size_t>(width));
    detail::fractal_noise_row(world_row0 + row, world_col0, noise, largest_cell, params.seed);
    for (int col = 0; col < width; ++col) {
      // noise + one lies in [0, 2 one]: heights lie in [0, relief].
      out.at(col, row) = float(double(noise[col] + detail::kNoiseOne) * metres_per_unit);
    }
  });
  return out;
}

std::string generated_name(const GeneratedTerrain& params) {
  return fmt::format("generated:seed={}", params.seed);
}

class GeneratedSource final : public HeightfieldSource {
 public:
  GeneratedSource(const GeneratedTerrain& params, std::string crs_wkt, std::int64_t copied_cells)
      : HeightfieldSource({params.width, params.height, params.origin_x, params.origin_y,
                           params.pixel_size, params.pixel_size},
                          std::move(crs_wkt), std::nullopt, generated_name(params)),
        params_(params),
        copied_cells_(copied_cells) {}

 protected:
  // The last window generated is kept and handed out when the same window is asked again: a
  // tile's render and its report facts (input height range) compute the noise once per pixel
  // (issue #23 item 4), at any window size. A window of up to copied_cells_ is copied out (and
  // stays for a third read); a larger one (an untiled world's) is moved out on its second read,
  // so the source holds at most one window's band, and only between those two reads.
  Raster<float> read_window(const Window& w) const override {
    const bool copy = std::int64_t(w.width) * w.height <= copied_cells_;
    {
      const std::lock_guard lock(mutex_);
      if (last_window_ == w && !last_.pixels.empty()) {
        if (copy) return last_;
        last_window_ = {};
        Raster<float> out = std::move(last_);
        last_ = {};
        return out;
      }
    }
    Raster<float> cells = generate_cells(params_, w.col0, w.row0, w.width, w.height);
    const std::lock_guard lock(mutex_);
    computed_ += std::int64_t(w.width) * w.height;
    last_window_ = w;
    last_ = cells;
    return cells;
  }

 public:
  std::int64_t computed() const {
    const std::lock_guard lock(mutex_);
    return computed_;
  }

 private:
  GeneratedTerrain params_;
  std::int64_t copied_cells_;
  mutable std::int64_t computed_ = 0;  // guarded by mutex_
  mutable std::mutex mutex_;  // guards last_window_ and last_
  mutable Window last_window_{};
  mutable Raster<float> last_;
};

}  // namespace

Heightfield generate_heightfield(const GeneratedTerrain& params) {
  const std::string name = generated_name(params);
  Heightfield result;
  result.source = name;
  result.crs_wkt = checked_crs_wkt(params, name);
  result.grid = {params.width,    params.height,     params.origin_x,
                 params.origin_y, params.pixel_size, params.pixel_size};
  result.height = generate_cells(params, 0, 0, params.width, params.height);
  return result;
}

std::unique_ptr<HeightfieldSource> open_generated_heightfield(const GeneratedTerrain& params) {
  return detail::open_generated_source(params, detail::kGeneratedCopiedCells);
}

std::unique_ptr<HeightfieldSource> open_generated_heightfield(const GeneratedTerrain& params,
                                                              std::string checked_crs_wkt) {
  check_generated_params(params, generated_name(params));
  return std::make_unique<GeneratedSource>(params, std::move(checked_crs_wkt),
                                           detail::kGeneratedCopiedCells);
}

std::unique_ptr<HeightfieldSource> detail::open_generated_source(const GeneratedTerrain& params,
                                                                 std::int64_t copied_cells) {
  return std::make_unique<GeneratedSource>(params, checked_crs_wkt(params, generated_name(params)),
                                           copied_cells);
}

std::int64_t detail::generated_cells(const HeightfieldSource& source) {
  const auto* generated = dynamic_cast<const GeneratedSource*>(&source);
  return generated ? generated->computed() : 0;
}

bool detail::is_generated_source(const HeightfieldSource& source) {
  return dynamic_cast<const GeneratedSource*>(&source) != nullptr;
}

}  // namespace tw
