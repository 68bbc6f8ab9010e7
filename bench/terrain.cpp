// Shaping + splat + writing time and peak memory on synthetic worlds of 1k^2, 4k^2 and 8k^2
// pixels (2 m pixels), with feature length proportional to the area: 500 km of roads and
// rivers on the 8k^2 grid. Each size runs in its own child process so that its peak RSS is
// its own. Usage: bench_terrain [size ...] [--keep DIR]. Prints numbers; never fails on time.
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "core/atomic_output.hpp"
#include "layers/write.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/splat.hpp"

namespace {

using namespace tw;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds of this process (user + system): with several engineers sharing two cores,
// wall time alone says little.
double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // KiB on Linux
}

Raster<float> rolling_hills(const GridSpec& grid) {
  Raster<float> h(grid.width, grid.height);
  tbb::parallel_for(0, grid.height, [&](int r) {
    for (int c = 0; c < grid.width; ++c) {
      const Vec2 p = grid.pixel_centre_world(c, r);
      const double x = p.x - grid.origin_x, y = grid.origin_y - p.y;
      h.at(c, r) = float(300.0 + 40.0 * std::sin(x / 700.0) * std::cos(y / 900.0) +
                         12.0 * std::sin((x + 2.0 * y) / 210.0) +
                         1.0 * std::sin((3.0 * x - y) / 150.0) + 0.002 * x);
    }
  });
  return h;
}

// Smooth random walks of 1-3 km, 10 m vertices, kept inside the grid: 60 % roads, 40 % rivers.
std::vector<TerrainFeature> random_features(const GridSpec& grid, double total_length) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double w = grid.width * grid.pixel_width, h = grid.height * grid.pixel_height;
  std::vector<TerrainFeature> out;
  double built = 0.0;
  while (built < total_length) {
    TerrainFeature f;
    f.fid = std::int64_t(out.size());
    f.kind = u(rng) < 0.6 ? FeatureKind::road : FeatureKind::river;
    f.width = f.kind == FeatureKind::road ? 6.0 : 10.0;
    Vec2 p{grid.origin_x + u(rng) * w, grid.origin_y - u(rng) * h};
    double heading = u(rng) * 2.0 * M_PI, turn = 0.0;
    const double length = std::min(total_length - built + 20.0, 1000.0 + 2000.0 * u(rng));
    f.centerline.points.push_back(p);
    for (double s = 0.0; s < length; s += 10.0) {
      turn = 0.9 * turn + 0.02 * (u(rng) - 0.5);
      heading += turn;
      Vec2 q = p + Vec2{std::cos(heading), std::sin(heading)} * 10.0;
      if (q.x < grid.origin_x || q.x > grid.origin_x + w || q.y > grid.origin_y ||
          q.y < grid.origin_y - h) {
        // Turn towards the centre of the world instead of running along its edge.
        const Vec2 centre{grid.origin_x + 0.5 * w, grid.origin_y - 0.5 * h};
        heading = std::atan2(centre.y - p.y, centre.x - p.x) + (u(rng) - 0.5);
        turn = 0.0;
        continue;
      }
      f.centerline.points.push_back(p = q);
    }
    built += arc_length(f.centerline);
    if (f.centerline.points.size() >= 2) out.push_back(std::move(f));
  }
  return out;
}

struct Timing {
  double wall = 0.0;
  double cpu = 0.0;
};

template <class F>
Timing timed(F&& f) {
  const double cpu0 = cpu_seconds();
  const auto t0 = Clock::now();
  f();
  return {seconds_since(t0), cpu_seconds() - cpu0};
}

void run(int size, const std::filesystem::path& dir) {
  GridSpec grid{size, size, 500000.0, 5100000.0, 2.0, 2.0};
  const double length = 500e3 * double(size) * size / (8192.0 * 8192.0);
  auto t0 = Clock::now();
  Raster<float> height = rolling_hills(grid);
  const auto features = random_features(grid, length);
  const double t_input = seconds_since(t0);

  TerrainPlan plan;
  const Timing plan_t = timed([&] { plan = plan_terrain(height, grid, features, {}); });
  const Timing shape_t = timed([&] { apply_terrain(height, grid, Window::whole(grid), plan); });
  SplatLayers splat;
  const Timing splat_t =
      timed([&] { splat = compute_splat(grid, Window::whole(grid), features, {}); });

  LayerSet set;
  set.grid = grid;
  set.crs_wkt = "EPSG:32631";
  set.nodata = -9999.0;
  set.layers.push_back(height_layer(std::move(height)));
  set.layers.push_back(splat_layer(std::move(splat)));
  Timing write_t[3];
  for (int kind = 0; kind < 3; ++kind) {
    WriteOptions o;
    o.exr = kind == 0;
    o.geotiff = kind == 1;
    o.preview = kind == 2;
    if (kind == 2)
      for (const auto& f : features) o.preview_lines.push_back(f.centerline.points);
    write_t[kind] = timed([&] {
      OutputTransaction tx;
      write_layer_set(set, dir, tx, o);
      tx.commit();
    });
  }
  const double layer_mib = 7.0 * 4.0 * double(size) * size / (1024.0 * 1024.0);
  Timing total;
  for (const Timing& t : {plan_t, shape_t, splat_t, write_t[0], write_t[1], write_t[2]})
    total.wall += t.wall, total.cpu += t.cpu;
  std::printf("%5d^2  %6.1f km  %5zu features  (wall / CPU seconds; input %.2f s)\n", size,
              length / 1e3, features.size(), t_input);
  const char* names[] = {"plan", "shape", "splat", "exr", "tif", "png", "TOTAL"};
  const Timing all[] = {plan_t, shape_t, splat_t, write_t[0], write_t[1], write_t[2], total};
  for (int i = 0; i < 7; ++i)
    std::printf("    %-6s %7.2f / %7.2f\n", names[i], all[i].wall, all[i].cpu);
  std::printf("    peak RSS %.0f MiB = %.2f x the layers written (%.0f MiB)\n", peak_rss_mib(),
              peak_rss_mib() / layer_mib, layer_mib);
  // The EXR compression trade-off per layer (docs/performance.md): seconds and size.
  std::filesystem::create_directories(dir);
  const std::pair<ExrCompression, const char*> compressions[] = {
      {ExrCompression::none, "none"}, {ExrCompression::rle, "rle"}, {ExrCompression::zip, "zip1"}};
  for (const Layer& layer : set.layers) {
    const double raw_mb = 4.0 * double(size) * size * double(layer.bands.size()) / 1e6;
    std::printf("    exr %-6s (%4.0f MB raw, automatic = %s):", layer.name.c_str(), raw_mb,
                exr_compression_for(layer) == ExrCompression::rle ? "rle" : "none");
    for (const auto& [compression, name] : compressions) {
      const auto path = dir / ("compression-" + layer.name + ".exr");
      const Timing t = timed([&] { write_exr(set, layer, path, compression); });
      std::printf("  %s %.2f s / %.2f cpu %5.1f%%", name, t.wall, t.cpu,
                  100.0 * double(std::filesystem::file_size(path)) / (raw_mb * 1e6));
      std::filesystem::remove(path);
    }
    std::printf("\n");
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  std::filesystem::path keep;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--keep" && i + 1 < argc)
      keep = argv[++i];
    else
      sizes.push_back(std::stoi(a));
  }
  if (sizes.empty()) sizes = {1024, 4096, 8192};
  for (const int size : sizes) {
    const auto dir = keep.empty() ? std::filesystem::temp_directory_path() /
                                        ("terraweave-bench-" + std::to_string(::getpid()))
                                  : keep / std::to_string(size);
    const pid_t child = fork();
    if (child == 0) {
      run(size, dir);
      std::_Exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    if (keep.empty()) std::filesystem::remove_all(dir);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) std::printf("%d^2: child failed\n", size);
  }
  return 0;
}
