// Polygon rasterization: tw::burn_polygons against GDALRasterizeGeometries (the library behind
// gdal_rasterize) on the same grid and polygons. Prints times, the speed ratio and how many
// pixels agree; never fails on time.
//   bench_rasterize [polygons=2000] [size=4096]
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogr_spatialref.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "raster/distance.hpp"
#include "raster/foldover.hpp"
#include "raster/rasterize.hpp"

namespace {

using tw::GridSpec;
using tw::Polygon;
using tw::Raster;
using tw::Vec2;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Seeded star-shaped polygons of 20..200 vertices; one in four has a hole.
std::vector<Polygon> random_polygons(int count, const GridSpec& grid, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const double extent_x = grid.width * grid.pixel_width, extent_y = grid.height * grid.pixel_height;
  std::uniform_real_distribution<double> cx(0.0, extent_x), cy(0.0, extent_y);
  std::uniform_real_distribution<double> size(0.01, 0.04);
  std::uniform_int_distribution<int> vertices(20, 200);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Polygon> polygons;
  for (int i = 0; i < count; ++i) {
    const Vec2 centre{grid.origin_x + cx(rng), grid.origin_y - cy(rng)};
    const double r = size(rng) * extent_x;
    auto star = [&](double r_min, double r_max, int n, double sign) {
      tw::Ring ring;
      for (int k = 0; k < n; ++k) {
        const double a = sign * 2.0 * std::numbers::pi * k / n;
        const double rr = r_min + (r_max - r_min) * unit(rng);
        ring.push_back(centre + Vec2{std::cos(a), std::sin(a)} * rr);
      }
      return ring;
    };
    Polygon p{star(0.4 * r, r, vertices(rng), 1.0)};
    if (i % 4 == 0) p.push_back(star(0.1 * r, 0.3 * r, 24, -1.0));
    polygons.push_back(std::move(p));
  }
  return polygons;
}

std::vector<OGRGeometryH> to_ogr(const std::vector<Polygon>& polygons) {
  std::vector<OGRGeometryH> out;
  for (const Polygon& polygon : polygons) {
    OGRGeometryH g = OGR_G_CreateGeometry(wkbPolygon);
    for (const auto& ring : polygon) {
      OGRGeometryH r = OGR_G_CreateGeometry(wkbLinearRing);
      for (const Vec2 p : ring) OGR_G_AddPoint_2D(r, p.x, p.y);
      OGR_G_AddPoint_2D(r, ring.front().x, ring.front().y);
      OGR_G_AddGeometryDirectly(g, r);
    }
    out.push_back(g);
  }
  return out;
}

Raster<std::uint8_t> gdal_burn(const std::vector<OGRGeometryH>& geometries, const GridSpec& grid,
                               double& elapsed) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  std::unique_ptr<GDALDataset> ds(mem->Create("", grid.width, grid.height, 1, GDT_Byte, nullptr));
  auto gt = grid.geotransform();
  ds->SetGeoTransform(gt.data());
  OGRSpatialReference srs;
  srs.SetFromUserInput("EPSG:32633");
  ds->SetSpatialRef(&srs);
  int band = 1;
  std::vector<double> burn(geometries.size(), 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  GDALRasterizeGeometries(GDALDataset::ToHandle(ds.get()), 1, &band, int(geometries.size()),
                          const_cast<OGRGeometryH*>(geometries.data()), nullptr, nullptr,
                          burn.data(), nullptr, nullptr, nullptr);
  // Reading back is part of getting a usable raster out of GDAL's MEM dataset.
  Raster<std::uint8_t> out(grid.width, grid.height, 0);
  if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, grid.width, grid.height, out.pixels.data(),
                                     grid.width, grid.height, GDT_Byte, 0, 0) != CE_None)
    std::fprintf(stderr, "RasterIO failed\n");
  elapsed = seconds_since(t0);
  return out;
}

Raster<std::uint8_t> tw_burn(const std::vector<Polygon>& polygons, const GridSpec& grid,
                             double& elapsed) {
  const auto t0 = std::chrono::steady_clock::now();
  Raster<std::uint8_t> out;
  tw::burn_polygons(polygons, grid, tw::Window::whole(grid), out, 1);
  elapsed = seconds_since(t0);
  return out;
}

void run_case(int count, int size) {
  const GridSpec grid{size, size, 500000.0, 5000000.0 + size * 1.0, 1.0, 1.0};
  const auto polygons = random_polygons(count, grid, 42);
  std::size_t vertex_total = 0;
  for (const auto& p : polygons)
    for (const auto& r : p) vertex_total += r.size();
  const auto geometries = to_ogr(polygons);
  constexpr int kRepeats = 5;
  double best_gdal = 1e30, best_tw = 1e30, best_tw1 = 1e30, elapsed = 0.0;
  Raster<std::uint8_t> gdal, ours;
  for (int i = 0; i < kRepeats; ++i) {
    gdal = gdal_burn(geometries, grid, elapsed);
    best_gdal = std::min(best_gdal, elapsed);
    ours = tw_burn(polygons, grid, elapsed);
    best_tw = std::min(best_tw, elapsed);
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      tw_burn(polygons, grid, elapsed);
      best_tw1 = std::min(best_tw1, elapsed);
    }
  }
  // Tiled: 4 x 4 tiles of the same grid, each burned on its own (what a tiled run does).
  const int tile = size / 4;
  const auto t0 = std::chrono::steady_clock::now();
  Raster<std::uint8_t> stitched(size, size, 0);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const tw::Window w{c * tile, r * tile, tile, tile};
      Raster<std::uint8_t> part;
      tw::burn_polygons(polygons, grid, w, part, 1);
      for (int y = 0; y < tile; ++y)
        std::copy_n(part.pixels.begin() + std::size_t(y) * tile, tile,
                    stitched.pixels.begin() + std::size_t(w.row0 + y) * size + w.col0);
    }
  const double tiled = seconds_since(t0);
  std::size_t same = 0, filled = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) {
    same += ours.pixels[i] == gdal.pixels[i];
    filled += ours.pixels[i] != 0;
  }
  std::printf("%d polygons (%zu vertices) on %dx%d, %d threads available\n", count, vertex_total,
              size, size, tbb::info::default_concurrency());
  std::printf("  GDALRasterizeGeometries : %8.2f ms\n", best_gdal * 1e3);
  std::printf("  tw::burn_polygons       : %8.2f ms  (GDAL / tw = %.2fx)\n", best_tw * 1e3,
              best_gdal / best_tw);
  std::printf("  tw::burn_polygons, 1 thr: %8.2f ms  (GDAL / tw = %.2fx)\n", best_tw1 * 1e3,
              best_gdal / best_tw1);
  std::printf("  tw, 16 tiles one by one : %8.2f ms  (tiles == whole: %s)\n", tiled * 1e3,
              stitched.pixels == ours.pixels ? "yes" : "NO");
  std::printf("  agreement with GDAL     : %.5f %% of %zu pixels (%zu filled, %zu differ)\n",
              100.0 * double(same) / double(ours.pixels.size()), ours.pixels.size(), filled,
              ours.pixels.size() - same);
  for (OGRGeometryH g : geometries) OGR_G_DestroyGeometry(g);

  // The other raster stages on the same grid, for scale.
  auto time_best = [](auto&& fn) {
    double best = 1e30;
    for (int i = 0; i < 3; ++i) {
      const auto t = std::chrono::steady_clock::now();
      fn();
      best = std::min(best, seconds_since(t));
    }
    return best;
  };
  const double coverage =
      time_best([&] { tw::polygon_coverage(polygons, grid, tw::Window::whole(grid), 4); });
  const double edt =
      time_best([&] { tw::distance_to_mask(ours, grid.pixel_width, grid.pixel_height); });
  std::printf("  polygon_coverage 4x4    : %8.2f ms\n", coverage * 1e3);
  std::printf("  distance_to_mask (EDT)  : %8.2f ms\n", edt * 1e3);
}

// Fold-overs of a long meandering ribbon (5 m wide, 1 m pieces) on a 1 m grid.
void run_foldover_case(int size) {
  tw::Curve meander;
  for (int i = 0; i <= 20 * size; ++i) {
    const double s = i * 0.05;
    meander.points.push_back(
        {500000.0 + s,
         5000000.0 + size / 2.0 + 0.2 * size * std::sin(s / 7.0) + 3.0 * std::sin(s / 1.3)});
  }
  const GridSpec grid{size, size, 500000.0, 5000000.0 + size, 1.0, 1.0};
  const tw::Ribbon ribbon = tw::make_ribbon(meander, {5.0, 1.0});
  double best = 1e30;
  std::size_t folded = 0;
  for (int i = 0; i < 3; ++i) {
    const auto t = std::chrono::steady_clock::now();
    const auto mask = tw::foldover_mask(ribbon, grid, tw::Window::whole(grid));
    best = std::min(best, seconds_since(t));
    folded = std::size_t(std::count(mask.pixels.begin(), mask.pixels.end(), 1));
  }
  std::printf("foldover_mask: %zu pieces on %dx%d: %8.2f ms (%zu fold-over pixels)\n",
              ribbon.pieces.size(), size, size, best * 1e3, folded);
}

}  // namespace

int main(int argc, char** argv) {
  GDALAllRegister();
  const int count = argc > 1 ? std::atoi(argv[1]) : 2000;
  const int size = argc > 2 ? std::atoi(argv[2]) : 4096;
  run_case(200, 512);
  run_case(count, size);
  run_foldover_case(size);
  return 0;
}
