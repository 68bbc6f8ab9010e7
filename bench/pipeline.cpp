// A full pipeline run on worlds of 1k^2, 4k^2 and 8k^2 cells (4 m) with seeded meandering roads
// and rivers in a temporary GeoPackage (8k^2: about 500 km of lines; fewer in proportion to the
// area below), over two kinds of heights (issue #23 item 5):
//   generated  the project's fractal noise (`generate:`), as every other benchmark uses;
//   dem        a real DEM file, as users run: --dem PATH (default: Luxembourg's 30" SRTM
//              elev.tif of Debian's r-cran-terra, else samples/dem.tif), warped by GDAL (cubic)
//              onto N^2 cells of 4 m in UTM, from the DEM's middle, into a tiled ZSTD GeoTIFF
//              before the run (not timed), and read by the pipeline as any `heightfield:`.
// Each run is a child process, so its peak memory (getrusage ru_maxrss) and CPU seconds (user +
// system) are its own. Prints time per stage, total wall, CPU seconds, peak RSS and the ratio
// of the peak to the bytes of the layers (float bands) written. Never fails on time.
//   bench_pipeline [--heights generated|dem|both] [--dem PATH] [sizes...]
//   e.g. bench_pipeline --heights both 1024 4096
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
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

// The world's north-west corner (metres, in its CRS): the generated world's, or the warped
// DEM's.
struct Corner {
  double x = 500000.0, y = 5000000.0;
  int epsg = 32631;
};

// A meander whose heading never turns more than ~70 degrees from its base direction, so it
// never crosses itself (crossings between lines are welcome: junctions).
std::unique_ptr<OGRLineString> meander(std::mt19937_64& rng, double extent, const Corner& corner) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double margin = 0.05 * extent;
  const double base = unit(rng) * 2.0 * M_PI;
  const double phase = unit(rng) * 2.0 * M_PI, wavelength = 300.0 + 600.0 * unit(rng);
  double x = margin + unit(rng) * (extent - 2 * margin),
         y = margin + unit(rng) * (extent - 2 * margin);
  auto line = std::make_unique<OGRLineString>();
  for (double s = 0.0; s <= kLineLength; s += 20.0) {
    line->addPoint(corner.x + x, corner.y - y);
    const double heading = base + 1.2 * std::sin(phase + 2.0 * M_PI * s / wavelength);
    x = std::clamp(x + 20.0 * std::cos(heading), 1.0, extent - 1.0);
    y = std::clamp(y + 20.0 * std::sin(heading), 1.0, extent - 1.0);
  }
  return line;
}

void write_world(const fs::path& gpkg, int cells, std::uint64_t seed, const Corner& corner) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(
      gpkg.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  OGRSpatialReference srs;
  srs.importFromEPSG(corner.epsg);
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
      feature.SetGeometryDirectly(meander(rng, extent, corner).release());
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

tw::PipelineConfig config_for(const fs::path& dir, int cells, const std::optional<fs::path>& dem,
                              const Corner& corner) {
  tw::PipelineConfig c;
  c.seed = 7;
  if (dem) {
    c.heightfield = *dem;
  } else {
    c.generate.width = c.generate.height = cells;
    c.generate.pixel_size = kPixel;
    c.generate.origin_x = corner.x;
    c.generate.origin_y = corner.y;
  }
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

// The middle of `source` warped onto cells^2 cells of kPixel m in the UTM zone of its centre
// (cubic; float32; tiled ZSTD GeoTIFF, as a user's prepared DEM). Returns the corner.
Corner warp_dem(const fs::path& source, const fs::path& out, int cells) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> in(GDALDataset::Open(source.c_str(), GDAL_OF_RASTER));
  if (!in) throw std::runtime_error("cannot open " + source.string());
  double gt[6];
  in->GetGeoTransform(gt);
  const double lon = gt[0] + gt[1] * in->GetRasterXSize() / 2.0;
  const double lat = gt[3] + gt[5] * in->GetRasterYSize() / 2.0;
  OGRSpatialReference wgs84, utm;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  Corner corner;
  corner.epsg = (lat >= 0 ? 32600 : 32700) + int(std::floor((lon + 180.0) / 6.0)) + 1;
  utm.importFromEPSG(corner.epsg);
  const OGRSpatialReference* source_srs = in->GetSpatialRef();
  const bool geographic = source_srs == nullptr || source_srs->IsGeographic();
  double cx = geographic ? lon : gt[0] + gt[1] * in->GetRasterXSize() / 2.0;
  double cy = geographic ? lat : gt[3] + gt[5] * in->GetRasterYSize() / 2.0;
  if (geographic) {
    std::unique_ptr<OGRCoordinateTransformation> to_utm(
        OGRCreateCoordinateTransformation(&wgs84, &utm));
    to_utm->Transform(1, &cx, &cy);
  } else {  // a projected DEM keeps its CRS (the GeoPackage's lines are written in it too)
    utm = *source_srs;
    const char* code = source_srs->GetAuthorityCode(nullptr);
    if (code == nullptr) throw std::runtime_error(source.string() + ": its CRS has no EPSG code");
    corner.epsg = std::atoi(code);
  }
  const double half = cells * kPixel / 2.0;
  corner.x = std::round(cx - half);
  corner.y = std::round(cy + half);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  const std::string target_srs = wkt;
  CPLFree(wkt);
  std::vector<std::string> args = {"-t_srs",  target_srs,   "-r",     "cubic",  "-ot",
                                   "Float32", "-dstnodata", "-32768", "-multi", "-overwrite"};
  args.insert(args.end(),
              {"-wo", "NUM_THREADS=ALL_CPUS", "-co", "TILED=YES", "-co", "COMPRESS=ZSTD", "-co",
               "ZSTD_LEVEL=1", "-ts", std::to_string(cells), std::to_string(cells), "-te"});
  for (const double bound : {corner.x, corner.y - 2 * half, corner.x + 2 * half, corner.y})
    args.push_back(std::to_string(bound));
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv.data(), nullptr);
  GDALDatasetH source_handle = GDALDataset::ToHandle(in.get());
  int usage_error = 0;
  GDALDatasetH warped = GDALWarp(out.c_str(), nullptr, 1, &source_handle, options, &usage_error);
  GDALWarpAppOptionsFree(options);
  if (warped == nullptr) throw std::runtime_error("cannot warp " + source.string());
  GDALClose(warped);
  return corner;
}

struct Job {
  int cells = 0;
  std::optional<fs::path> dem;  // the warped DEM; absent: generated heights
  Corner corner;
};

int run_child(const Job& job) {
  tw::set_log_level(spdlog::level::warn);
  const fs::path dir =
      fs::temp_directory_path() / ("terraweave-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_world(dir / "world.gpkg", job.cells, 42, job.corner);
  const tw::RunReport report = tw::run_pipeline(config_for(dir, job.cells, job.dem, job.corner));
  for (const auto& s : report.stages) std::printf("  %-10s %8.2f s\n", s.stage.c_str(), s.seconds);
  std::printf("  %-10s %8.2f s\n", "total", report.total_seconds);
  std::uintmax_t bytes_on_disk = 0;
  for (const auto& f : report.outputs) bytes_on_disk += fs::file_size(f);
  std::printf("  files      %8.1f MB on disk\n", bytes_on_disk / 1e6);
  std::fflush(stdout);
  fs::remove_all(dir);
  return 0;
}

// warp_dem in a child process: GDAL's warper starts worker threads, and a process forked
// after that (the run's child) would wait forever on a pool whose threads it has not got.
std::optional<Corner> warp_in_child(const fs::path& dem, const fs::path& out, int cells) {
  int fds[2];
  if (::pipe(fds) != 0) return std::nullopt;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    try {
      const Corner corner = warp_dem(dem, out, cells);
      ::_exit(::write(fds[1], &corner, sizeof corner) == ssize_t(sizeof corner) ? 0 : 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench: %s\n", e.what());
      ::_exit(1);
    }
  }
  ::close(fds[1]);
  Corner corner;
  const bool read_all = ::read(fds[0], &corner, sizeof corner) == ssize_t(sizeof corner);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!read_all || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return corner;
}

double seconds(const timeval& t) {
  return double(t.tv_sec) + double(t.tv_usec) / 1e6;
}

fs::path default_dem() {
  const fs::path terra = "/usr/lib/R/site-library/terra/ex/elev.tif";  // r-cran-terra
  if (fs::exists(terra)) return terra;
  return fs::path(TERRAWEAVE_SOURCE_DIR) / "samples" / "dem.tif";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  std::string heights = "both";
  fs::path dem = default_dem();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--heights" && i + 1 < argc) {
      heights = argv[++i];
    } else if (arg == "--dem" && i + 1 < argc) {
      dem = argv[++i];
    } else {
      sizes.push_back(std::atoi(argv[i]));
    }
  }
  if (sizes.empty()) sizes = {1024, 4096, 8192};
  std::vector<std::string> kinds;
  if (heights == "generated" || heights == "both") kinds.push_back("generated");
  if (heights == "dem" || heights == "both") kinds.push_back("dem");
  if (kinds.empty()) {
    std::fprintf(stderr, "bench_pipeline: --heights is generated, dem or both\n");
    return 2;
  }
  double load[3] = {0, 0, 0};
  if (::getloadavg(load, 3) == 3)
    std::printf("load average %.2f %.2f %.2f at the start\n", load[0], load[1], load[2]);
  for (const int cells : sizes) {
    for (const std::string& kind : kinds) {
      Job job;
      job.cells = cells;
      const fs::path warped = fs::temp_directory_path() /
                              ("terraweave-bench-dem-" + std::to_string(::getpid()) + ".tif");
      if (kind == "dem") {
        job.dem = warped;
        const std::optional<Corner> corner = warp_in_child(dem, warped, cells);
        if (!corner) return 1;
        job.corner = *corner;
        std::printf("%d^2 cells, DEM %s warped to %.0f m cells (EPSG:%d, corner %.0f %.0f)\n",
                    cells, dem.c_str(), kPixel, job.corner.epsg, job.corner.x, job.corner.y);
      } else {
        std::printf("%d^2 cells, generated heights\n", cells);
      }
      std::fflush(stdout);
      const pid_t pid = ::fork();
      if (pid == 0) {
        try {
          ::_exit(run_child(job));
        } catch (const std::exception& e) {
          std::fprintf(stderr, "bench: %s\n", e.what());
          ::_exit(1);
        }
      }
      int status = 0;
      rusage usage{};
      ::wait4(pid, &status, 0, &usage);
      std::error_code ec;
      fs::remove(warped, ec);
      // 9 float bands: height, 6 splat materials, forbidden, distance.
      const double layer_bytes = 9.0 * 4.0 * double(cells) * cells;
      const double peak = double(usage.ru_maxrss) * 1024.0;
      std::printf("  cpu        %8.2f s (user %.2f + system %.2f)\n",
                  seconds(usage.ru_utime) + seconds(usage.ru_stime), seconds(usage.ru_utime),
                  seconds(usage.ru_stime));
      std::printf("  peak RSS   %8.1f MB, layers %.1f MB, peak / layers %.2f%s\n", peak / 1e6,
                  layer_bytes / 1e6, peak / layer_bytes,
                  WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : "  (child failed)");
      std::fflush(stdout);
    }
  }
  return 0;
}
