// A full pipeline run on generated worlds of 1k^2, 4k^2 and 8k^2 cells (4 m) with seeded
// meandering roads and rivers in a temporary GeoPackage (8k^2: about 500 km of lines; fewer in
// proportion to the area below). Each size runs in a child process so that peak memory
// (getrusage ru_maxrss) is its own. Prints time per stage, total, peak RSS and the ratio of the
// peak to the bytes of the layers (float bands) written. Never fails on time.
//   bench_pipeline [sizes...]   e.g. bench_pipeline 1024 4096
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/log.hpp"
#include "pipeline/run.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kPixel = 4.0;
constexpr double kLineLength = 2000.0;  // metres per line
constexpr double kOriginX = 500000.0, kOriginY = 5000000.0;

// A meander whose heading never turns more than ~70 degrees from its base direction, so it
// never crosses itself (crossings between lines are welcome: junctions).
std::unique_ptr<OGRLineString> meander(std::mt19937_64& rng, double extent) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double margin = 0.05 * extent;
  const double base = unit(rng) * 2.0 * M_PI;
  const double phase = unit(rng) * 2.0 * M_PI, wavelength = 300.0 + 600.0 * unit(rng);
  double x = margin + unit(rng) * (extent - 2 * margin),
         y = margin + unit(rng) * (extent - 2 * margin);
  auto line = std::make_unique<OGRLineString>();
  for (double s = 0.0; s <= kLineLength; s += 20.0) {
    line->addPoint(kOriginX + x, kOriginY - y);
    const double heading = base + 1.2 * std::sin(phase + 2.0 * M_PI * s / wavelength);
    x = std::clamp(x + 20.0 * std::cos(heading), 1.0, extent - 1.0);
    y = std::clamp(y + 20.0 * std::sin(heading), 1.0, extent - 1.0);
  }
  return line;
}

void write_world(const fs::path& gpkg, int cells, std::uint64_t seed) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(
      gpkg.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  OGRSpatialReference srs;
  srs.importFromEPSG(32631);
  const double extent = cells * kPixel;
  // 500 km over 8192^2 cells, in proportion to the area elsewhere; half roads, half rivers.
  const double total_km = 500.0 * (double(cells) * cells) / (8192.0 * 8192.0);
  const int lines_per_layer = std::max(1, int(std::lround(total_km * 1000.0 / kLineLength / 2.0)));
  std::mt19937_64 rng(seed);
  for (const char* name : {"roads", "rivers"}) {
    OGRLayer* layer = ds->CreateLayer(name, &srs, wkbLineString, nullptr);
    if (layer == nullptr || layer->StartTransaction() != OGRERR_NONE)
      throw std::runtime_error("cannot write the world");
    for (int i = 0; i < lines_per_layer; ++i) {
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetGeometryDirectly(meander(rng, extent).release());
      if (layer->CreateFeature(&feature) != OGRERR_NONE)
        throw std::runtime_error("cannot write a line");
    }
    if (layer->CommitTransaction() != OGRERR_NONE)
      throw std::runtime_error("cannot commit the world");
  }
  std::printf("  world: %d^2 cells of %.0f m, %d roads + %d rivers of %.0f m (%.0f km)\n", cells,
              kPixel, lines_per_layer, lines_per_layer, kLineLength,
              2.0 * lines_per_layer * kLineLength / 1000.0);
}

tw::PipelineConfig config_for(const fs::path& dir, int cells) {
  tw::PipelineConfig c;
  c.seed = 7;
  c.generate.width = c.generate.height = cells;
  c.generate.pixel_size = kPixel;
  c.generate.origin_x = kOriginX;
  c.generate.origin_y = kOriginY;
  c.output.dir = dir / "out";
  c.backend = "cpu";
  tw::FeatureClassConfig rivers;
  rivers.name = "rivers";
  rivers.source = dir / "world.gpkg";
  rivers.layer = "rivers";
  rivers.kind = tw::FeatureKind::river;
  rivers.width = 12.0;
  tw::FeatureClassConfig roads = rivers;
  roads.name = "roads";
  roads.layer = "roads";
  roads.kind = tw::FeatureKind::road;
  roads.width = 8.0;
  c.features = {rivers, roads};
  return c;
}

int run_child(int cells) {
  tw::set_log_level(spdlog::level::warn);
  const fs::path dir =
      fs::temp_directory_path() / ("terraweave-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_world(dir / "world.gpkg", cells, 42);
  const tw::RunReport report = tw::run_pipeline(config_for(dir, cells));
  for (const auto& s : report.stages) std::printf("  %-10s %8.2f s\n", s.stage.c_str(), s.seconds);
  std::printf("  %-10s %8.2f s\n", "total", report.total_seconds);
  std::uintmax_t bytes_on_disk = 0;
  for (const auto& f : report.outputs) bytes_on_disk += fs::file_size(f);
  std::printf("  files      %8.1f MB on disk\n", bytes_on_disk / 1e6);
  std::fflush(stdout);
  fs::remove_all(dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {1024, 4096, 8192};
  for (const int cells : sizes) {
    std::printf("%d^2 cells\n", cells);
    std::fflush(stdout);
    const pid_t pid = ::fork();
    if (pid == 0) {
      try {
        ::_exit(run_child(cells));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench: %s\n", e.what());
        ::_exit(1);
      }
    }
    int status = 0;
    rusage usage{};
    ::wait4(pid, &status, 0, &usage);
    // 9 float bands: height, 6 splat materials, forbidden, distance.
    const double layer_bytes = 9.0 * 4.0 * double(cells) * cells;
    const double peak = double(usage.ru_maxrss) * 1024.0;
    std::printf("  peak RSS   %8.1f MB, layers %.1f MB, peak / layers %.2f%s\n", peak / 1e6,
                layer_bytes / 1e6, peak / layer_bytes,
                WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : "  (child failed)");
    std::fflush(stdout);
  }
  return 0;
}
