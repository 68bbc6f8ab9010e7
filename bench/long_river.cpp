// Memory follows the ribbon (issue #8, item 7): one meandering river running diagonally across a
// generated 50 m world, with cobbles synthesized along it on 1 m canvas cells. Each run is the
// terraweave CLI in a child process, so that its time and peak RSS (wait4's ru_maxrss) are its
// own; a second binary (e.g. one built before the sparse canvas) runs the same inputs beside it.
// Prints, per river length: canvas size (its bounding box in cells), wall time, synthesis
// stage time and peak RSS. Never fails on time.
//   bench_long_river [--baseline PATH] [--baseline-max-km K] [km...]   default: 10 20 30 100
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr double kWorldPixel = 50.0;  // metres per world cell
constexpr double kMargin = 1000.0;    // metres of world around the river's box
constexpr double kOriginX = 500000.0, kOriginY = 5000000.0;

struct River {
  std::vector<std::pair<double, double>> points;  // relative to the box's south-west corner
  double width_m = 0, height_m = 0;               // of the box
};

// A river heading north-east, its heading swinging +-0.6 rad every 3 km, sampled every 20 m.
River diagonal_meander(double length_m) {
  River river;
  double x = 0, y = 0, min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  for (double s = 0.0; s <= length_m; s += 20.0) {
    river.points.emplace_back(x, y);
    min_x = std::min(min_x, x), max_x = std::max(max_x, x);
    min_y = std::min(min_y, y), max_y = std::max(max_y, y);
    const double heading = M_PI / 4 + 0.6 * std::sin(2.0 * M_PI * s / 3000.0);
    x += 20.0 * std::cos(heading);
    y += 20.0 * std::sin(heading);
  }
  for (auto& [px, py] : river.points) px -= min_x, py -= min_y;
  river.width_m = max_x - min_x;
  river.height_m = max_y - min_y;
  return river;
}

// The world, the river and the pipeline in `dir`; returns the pipeline's path.
fs::path write_inputs(const fs::path& dir, double length_km) {
  fs::create_directories(dir);
  const River river = diagonal_meander(length_km * 1000.0);
  const int cells_x = int(std::ceil((river.width_m + 2 * kMargin) / kWorldPixel));
  const int cells_y = int(std::ceil((river.height_m + 2 * kMargin) / kWorldPixel));
  const double south = kOriginY - cells_y * kWorldPixel;
  {
    std::ofstream geojson(dir / "river.geojson");
    geojson.precision(12);
    geojson << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": )"
            << R"({"name": "EPSG:32631"}}, "features": [{"type": "Feature", "id": 1, )"
            << R"("properties": {}, "geometry": {"type": "LineString", "coordinates": [)";
    for (std::size_t i = 0; i < river.points.size(); ++i)
      geojson << (i ? "," : "") << "[" << kOriginX + kMargin + river.points[i].first << ","
              << south + kMargin + river.points[i].second << "]";
    geojson << "]}}]}\n";
  }
  const fs::path exemplars = fs::path(TERRAWEAVE_SOURCE_DIR) / "samples/exemplars";
  fs::copy_file(exemplars / "cobble_edging_200x56.png", dir / "cobble.png",
                fs::copy_options::overwrite_existing);
  std::ofstream(dir / "river.yaml")
      << "version: 1\nseed: 5\n"
      << "generate: { width: " << cells_x << ", height: " << cells_y
      << ", pixel_size: " << kWorldPixel << ", origin: [" << kOriginX << ", " << kOriginY << "] }\n"
      << R"(output: { dir: out, geotiff: false, preview: false }
synthesis_resolution: 1
features:
  rivers:
    source: river.geojson
    kind: river
    width: 10
    synthesis: { exemplar: cobble.png, width: 8, scale: 4, delta: 16 }
)";
  return dir / "river.yaml";
}

struct Measure {
  bool ok = false;
  double wall_s = 0, synthesis_s = 0, peak_mb = 0;
  long long canvas_cells = 0;
  int canvas_w = 0, canvas_h = 0;
};

Measure run_cli(const std::string& binary, const fs::path& pipeline, const fs::path& out) {
  Measure m;
  fs::remove_all(out);
  std::fflush(stdout);  // or the child's freopen writes our pending lines again
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    // The CLI's own summary and errors go to a log beside the outputs.
    const fs::path log = out.string() + ".log";
    if (std::freopen(log.c_str(), "w", stdout) == nullptr) _exit(126);
    dup2(fileno(stdout), fileno(stderr));
    execl(binary.c_str(), binary.c_str(), "-q", "run", pipeline.c_str(), "--out", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.peak_mb = usage.ru_maxrss / 1024.0;
  m.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!m.ok) return m;
  std::ifstream in(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const auto& stage : report["timings"]["stages"])
    if (stage["stage"] == "synthesis") m.synthesis_s = stage["seconds"].get<double>();
  const auto& canvas = report["classes"][0]["features"][0]["synthesis"]["canvas"];
  m.canvas_w = canvas[0].get<int>();
  m.canvas_h = canvas[1].get<int>();
  m.canvas_cells = static_cast<long long>(m.canvas_w) * m.canvas_h;
  return m;
}

// Every output but report.json (which holds timings) byte for byte.
bool same_outputs(const fs::path& a, const fs::path& b) {
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file() || entry.path().filename() == "report.json") continue;
    const fs::path other = b / fs::relative(entry.path(), a);
    if (!fs::exists(other) || bytes(entry.path()) != bytes(other)) return false;
    ++files;
  }
  return files > 0;
}

void print(const char* label, double km, const Measure& m) {
  if (!m.ok) {
    std::printf("%-9s %6.0f km: failed (peak RSS %.0f MB, %.1f s; see its .log)\n", label, km,
                m.peak_mb, m.wall_s);
  } else {
    std::printf(
        "%-9s %6.0f km: canvas %6d x %6d (%7.1f M cells), total %7.1f s, synthesis %7.1f s, peak "
        "RSS %7.0f MB\n",
        label, km, m.canvas_w, m.canvas_h, m.canvas_cells / 1e6, m.wall_s, m.synthesis_s,
        m.peak_mb);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string baseline;
  double baseline_max_km = 30.0;
  std::vector<double> lengths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--baseline" && i + 1 < argc) {
      baseline = argv[++i];
    } else if (arg == "--baseline-max-km" && i + 1 < argc) {
      baseline_max_km = std::atof(argv[++i]);
    } else {
      lengths.push_back(std::atof(arg.c_str()));
    }
  }
  if (lengths.empty()) lengths = {10, 20, 30, 100};
  const fs::path dir = fs::temp_directory_path() / "tw_bench_long_river";
  for (const double km : lengths) {
    const fs::path pipeline = write_inputs(dir, km);
    const Measure ours = run_cli(TERRAWEAVE_CLI, pipeline, dir / "out");
    print("this", km, ours);
    if (!baseline.empty() && km <= baseline_max_km) {
      const Measure theirs = run_cli(baseline, pipeline, dir / "out_baseline");
      print("baseline", km, theirs);
      if (ours.ok && theirs.ok)
        std::printf("          outputs (placements, layers) byte-identical: %s\n",
                    same_outputs(dir / "out", dir / "out_baseline") ? "yes" : "NO");
    }
  }
  std::printf("inputs and logs of the last length: %s\n", dir.c_str());
  return 0;
}
