// Bytes and encode time of every layer of finished runs under each EXR compression (float32 and
// half) and GeoTIFF encoding, against the stock tools encoding the same pixels: `oiiotool
// --compression zip` (EXR) and `gdal_translate -co COMPRESS=ZSTD` (GeoTIFF), both from an
// uncompressed copy. Usage: bench_layer_codecs RUN_DIR ... (the <layer>.exr files of each run
// are read back: write them as float32, e.g. `output.exr_half: false`). docs/performance.md
// has the numbers. Prints numbers; never fails on time.
#include <ImfThreading.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "layers/write.hpp"

namespace {

using namespace tw;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Timing {
  double wall_ms = 0, cpu_ms = 0;
};

double cpu_ms(int who) {
  rusage usage{};
  getrusage(who, &usage);
  return 1e3 * double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-3 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The best of `repeats` (the machine is shared: the fastest run is the least disturbed).
template <typename F>
Timing timed(F&& f, int who = RUSAGE_SELF, int repeats = 2) {
  Timing best{1e300, 1e300};
  for (int i = 0; i < repeats; ++i) {
    const double c0 = cpu_ms(who);
    const auto t0 = Clock::now();
    f();
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (wall < best.wall_ms) best = {wall, cpu_ms(who) - c0};
  }
  return best;
}

void run_tool(const std::string& command) {
  if (std::system((command + " >/dev/null 2>&1").c_str()) != 0)
    std::fprintf(stderr, "failed: %s\n", command.c_str());
}

// Largest |difference| between what was written and what reads back (0: lossless).
double max_error(const Layer& layer, const fs::path& path) {
  const ExrContents back = read_exr(path);
  double worst = 0;
  for (std::size_t b = 0; b < layer.bands.size(); ++b)
    for (std::size_t i = 0; i < layer.bands[b].pixels.size(); ++i) {
      const float a = layer.bands[b].pixels[i], c = back.bands[b].pixels[i];
      if (std::isnan(a) != std::isnan(c)) return INFINITY;
      if (!std::isnan(a)) worst = std::max(worst, double(std::fabs(a - c)));
    }
  return worst;
}

void bench_run(const fs::path& run, const fs::path& scratch) {
  struct Codec {
    ExrCompression compression;
    const char* name;
    int level;
  };
  const Codec codecs[] = {{ExrCompression::none, "none", 1},     {ExrCompression::rle, "rle", 1},
                          {ExrCompression::zips, "zips", 1},     {ExrCompression::zip, "zip", 1},
                          {ExrCompression::zip, "zip4", 4},      {ExrCompression::piz, "piz", 1},
                          {ExrCompression::pxr24, "pxr24", 1},   {ExrCompression::b44, "b44", 1},
                          {ExrCompression::dwaa, "dwaa", 1},     {ExrCompression::dwab, "dwab", 1},
                          {ExrCompression::automatic, "auto", 1}};
  std::printf("== %s\n", run.string().c_str());
  for (const auto& entry : fs::directory_iterator(run)) {
    if (entry.path().extension() != ".exr") continue;
    const ExrContents contents = read_exr(entry.path());
    LayerSet set;
    set.grid = {contents.width,    contents.height,       contents.origin.x,
                contents.origin.y, contents.pixel_size.x, contents.pixel_size.y};
    set.crs_wkt = contents.crs_wkt;
    Layer& layer = set.layers.emplace_back();
    layer.name = entry.path().stem().string();
    layer.channels = contents.channels;
    layer.bands = contents.bands;
    const double raw_mb =
        4e-6 * double(contents.width) * contents.height * double(layer.bands.size());
    std::printf("-- %s: %d x %d x %zu bands, %.1f MB as float32 (automatic: %s, %s)\n",
                layer.name.c_str(), contents.width, contents.height, layer.bands.size(), raw_mb,
                to_string(exr_compression_for(layer)),
                exr_half_for(layer, ExrPixels::automatic) ? "half" : "float");
    std::printf("   %-14s %10s %9s %9s %8s %s\n", "codec", "bytes", "wall ms", "cpu ms", "% raw",
                "max error");
    const fs::path out = scratch / (layer.name + ".exr");
    // BENCH_CODECS=rle,zip limits the EXR codecs; BENCH_EXR_THREADS=n sizes OpenEXR's pool.
    const char* only = std::getenv("BENCH_CODECS");
    if (const char* threads = std::getenv("BENCH_EXR_THREADS")) {
      write_exr(set, layer, out, ExrCompression::none);  // starts the pool at its default first
      Imf::setGlobalThreadCount(std::atoi(threads));
    }
    for (const bool half : {false, true}) {
      for (const Codec& c : codecs) {
        if (only && !std::strstr(only, c.name)) continue;
        const ExrPixels pixels = half ? ExrPixels::half : ExrPixels::float32;
        const Timing t = timed([&] { write_exr(set, layer, out, c.compression, c.level, pixels); });
        const auto bytes = fs::file_size(out);
        std::printf("   exr %-5s %-4s %10ju %9.0f %9.0f %7.2f%% %g\n", c.name,
                    half ? "half" : "f32", std::uintmax_t(bytes), t.wall_ms, t.cpu_ms,
                    100.0 * double(bytes) / (raw_mb * 1e6), max_error(layer, out));
      }
    }
    if (std::getenv("BENCH_EXR_ONLY")) continue;
    struct Tiff {
      TiffCompression compression;
      TiffPredictor predictor;
      const char* name;
    };
    const Tiff tiffs[] = {{TiffCompression::none, TiffPredictor::none, "none"},
                          {TiffCompression::zstd, TiffPredictor::none, "zstd"},
                          {TiffCompression::zstd, TiffPredictor::floating_point, "zstd+fp"},
                          {TiffCompression::deflate, TiffPredictor::none, "deflate"}};
    const fs::path tif = scratch / (layer.name + ".tif");
    for (const Tiff& t : tiffs) {
      GeoTiffOptions options;
      options.compression = t.compression;
      options.predictor = t.predictor;
      const Timing time = timed([&] { write_geotiff(set, layer, tif, options); });
      const auto bytes = fs::file_size(tif);
      std::printf("   tif %-10s %10ju %9.0f %9.0f %7.2f%%\n", t.name, std::uintmax_t(bytes),
                  time.wall_ms, time.cpu_ms, 100.0 * double(bytes) / (raw_mb * 1e6));
    }
    // The stock tools, from uncompressed copies (reading them is part of their time).
    const fs::path raw_exr = scratch / (layer.name + "-raw.exr");
    const fs::path raw_tif = scratch / (layer.name + "-raw.tif");
    write_exr(set, layer, raw_exr, ExrCompression::none);
    GeoTiffOptions raw;
    raw.compression = TiffCompression::none;
    write_geotiff(set, layer, raw_tif, raw);
    const fs::path tool_out = scratch / (layer.name + "-tool");
    for (const char* type : {"float", "half"}) {
      const std::string command = "oiiotool " + raw_exr.string() + " -d " + type +
                                  " --compression zip -o " + tool_out.string() + ".exr";
      const Timing t = timed([&] { run_tool(command); }, RUSAGE_CHILDREN);
      std::printf("   oiiotool zip %-5s %10ju %9.0f %9.0f\n", type,
                  std::uintmax_t(fs::file_size(tool_out.string() + ".exr")), t.wall_ms, t.cpu_ms);
    }
    const std::string gdal =
        "gdal_translate -q -co TILED=YES -co COMPRESS=ZSTD -co ZSTD_LEVEL=1 "
        "-co NUM_THREADS=ALL_CPUS -co INTERLEAVE=BAND " +
        raw_tif.string() + " " + tool_out.string() + ".tif";
    const Timing g =
        timed([&] { run_tool("rm -f " + tool_out.string() + ".tif; " + gdal); }, RUSAGE_CHILDREN);
    std::printf("   gdal_translate zstd %10ju %9.0f %9.0f\n",
                std::uintmax_t(fs::file_size(tool_out.string() + ".tif")), g.wall_ms, g.cpu_ms);
    for (const auto& p : {out, tif, raw_exr, raw_tif, fs::path(tool_out.string() + ".exr"),
                          fs::path(tool_out.string() + ".tif")})
      fs::remove(p);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_layer_codecs RUN_DIR ...\n");
    return 2;
  }
  const fs::path scratch =
      fs::temp_directory_path() / ("terraweave-codecs-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  for (int i = 1; i < argc; ++i) bench_run(argv[i], scratch);
  fs::remove_all(scratch);
}
