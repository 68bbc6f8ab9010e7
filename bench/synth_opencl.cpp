// DP rows on the OpenCL backend (PoCL here) against the CPU reference: ms per row for the
// paper's exemplar sizes (199x82 and 325x64, from samples/exemplars/), time versus the number
// of pieces N and versus the exemplar width W (the paper's performance figure), ratios to the
// paper's GTX 580 figures (30 ms and 650 ms per row) and to the CPU backend, and where the
// OpenCL time goes (device time per kernel from profiling events; the host-side gap, the row
// update's wall time less its kernel's device time, and the host's phases of a row). Prints
// numbers only.
//
// usage: bench_synth_opencl [--quick | --cases] [--rows R] [--group G] [--per-item K]
//                           [--texels DIR | --save-texels DIR]
//   --quick: fewer rows and sizes; --cases: the two exemplars only (R rows each, default 3);
//   --save-texels: write the two exemplars' cost texels to DIR/<name>.texels and stop;
//   --texels: read them from there instead of decoding the PNGs (a machine that has no image
//   libraries: bench/device/bundle.sh);
//   --group / --per-item: the row kernel's work-group size and positions per work-item
//   (OpenCLRowOptions; results are identical for every choice). bench/device/run.sh runs it
//   on every OpenCL device.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/log.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/exemplar.hpp"

namespace {

using namespace tw;
using detail::CostTexels;

// A gentle arc (radius 400 texels) sliced into `pieces` pieces of 12 texels, ribbon width = H
// texels (C = H, the paper's typical case), one texel per metre.
detail::DpInput make_input(const CostTexels& texels, int pieces) {
  const double delta = 12.0, width = texels.height, radius = 400.0;
  const double length = delta * pieces;
  Curve curve;
  for (int i = 0; i <= 4 * pieces; ++i) {
    const double a = length / radius * i / (4.0 * pieces);
    curve.points.push_back({radius * std::sin(a), radius * (1 - std::cos(a))});
  }
  const Ribbon ribbon = make_ribbon(curve, {width, delta});
  GridSpec canvas;
  canvas.width = canvas.height = 16;
  detail::DpInput input;
  input.texels = &texels;
  const int column = detail::column_count(width, 1.0);
  input.space = {texels.width, texels.height, column};
  for (const Piece& piece : ribbon.pieces)
    input.pieces.push_back(detail::make_piece_footprint(piece, 1.0, column, canvas, nullptr));
  input.allow_empty = true;
  return input;
}

CostTexels crop(const CostTexels& texels, int width) {
  CostTexels out{width, texels.height, {}, texels.binary_alpha};
  for (int y = 0; y < texels.height; ++y)
    for (int x = 0; x < width; ++x)
      out.rgba.push_back(texels.rgba[y * texels.width + x % texels.width]);
  return out;
}

// A chain-like pattern when the sample exemplars are missing: elliptic links on transparent.
CostTexels generated_chain(int width, int height) {
  CostTexels t{width, height, std::vector<std::uint32_t>(std::size_t(width) * height, 0), true};
  const int link = height / 2;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double cx = (x / link + 0.5) * link, cy = height / 2.0;
      const double e = std::hypot((x + 0.5 - cx) / (0.6 * link), (y + 0.5 - cy) / (0.35 * height));
      if (e > 0.65 && e < 1.0) {
        const std::uint32_t v = std::uint32_t(90 + 150 * (1 - e)) & 255;
        t.rgba[std::size_t(y) * width + x] = v | v << 8 | (v / 2) << 16 | 255u << 24;
      }
    }
  return t;
}

// DIR/<stem>.texels: "TWTX", then width, height, binary_alpha and the packed texels, as
// little-endian 32-bit words (the bench's own exchange file; x86-64 and ARM hosts alike).
std::filesystem::path texels_path(const std::string& dir, const std::string& name) {
  return std::filesystem::path(dir) / (std::filesystem::path(name).stem().string() + ".texels");
}

void save_texels(const CostTexels& texels, const std::filesystem::path& path) {
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) throw std::runtime_error("cannot write " + path.string());
  const std::uint32_t header[4] = {0x58545754u, std::uint32_t(texels.width),
                                   std::uint32_t(texels.height), texels.binary_alpha ? 1u : 0u};
  const bool ok = std::fwrite(header, sizeof header, 1, out) == 1 &&
                  std::fwrite(texels.rgba.data(), 4, texels.rgba.size(), out) == texels.rgba.size();
  if (std::fclose(out) != 0 || !ok) throw std::runtime_error("cannot write " + path.string());
}

std::optional<CostTexels> read_texels(const std::filesystem::path& path) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) return std::nullopt;
  std::uint32_t header[4] = {};
  CostTexels texels;
  bool ok = std::fread(header, sizeof header, 1, in) == 1 && header[0] == 0x58545754u &&
            header[1] > 0 && header[2] > 0 && header[1] * std::uint64_t(header[2]) < (1u << 26);
  if (ok) {
    texels = {int(header[1]), int(header[2]), std::vector<std::uint32_t>(header[1] * header[2]),
              header[3] != 0};
    ok = std::fread(texels.rgba.data(), 4, texels.rgba.size(), in) == texels.rgba.size();
  }
  std::fclose(in);
  if (!ok) throw std::runtime_error("not a texels file: " + path.string());
  return texels;
}

std::string texels_dir;  // --texels DIR

CostTexels exemplar_texels(const std::string& name, int width, int height) {
  if (!texels_dir.empty())
    if (auto texels = read_texels(texels_path(texels_dir, name))) return *texels;
  const std::filesystem::path path =
      std::filesystem::path(TERRAWEAVE_SOURCE_DIR) / "samples/exemplars" / name;
  if (std::filesystem::exists(path)) return load_exemplar(path.string()).cost;
  std::printf("  (%s missing: generated %dx%d chain)\n", path.c_str(), width, height);
  return generated_chain(width, height);
}

struct RowTiming {
  double ms_per_row = 0;  // find + compact + extract + update, per DP row
  double update_ms_per_row = 0;
  double mean_valid = 0;
  std::int64_t cost = 0;
};

RowTiming time_dp(detail::Backend& backend, const detail::DpInput& input) {
  const detail::DpResult r = detail::run_dp(backend, input);
  const detail::DpTimings& t = r.timings;
  RowTiming out;
  const double rows = std::max(1, t.rows);
  out.ms_per_row = (t.find_valid_ms + t.compact_ms + t.extract_ms + t.update_ms) / rows;
  out.update_ms_per_row = t.update_ms / rows;
  double valid = 0;
  for (int v : r.valid_counts) valid += v;
  out.mean_valid = valid / std::max<std::size_t>(1, r.valid_counts.size());
  out.cost = r.total_cost;
  return out;
}

// Device time per kernel, then where the rest of the update's wall time goes: the host-side
// gap (update wall minus the row kernel's device time) and the host's phases of a row.
void print_kernel_times(const detail::OpenCLBackend& backend, int rows, double update_ms_per_row) {
  const double per_row = 1.0 / std::max(1, rows);
  double row_kernel_ms = 0;
  for (const auto& [name, timing] : backend.timings()) {
    std::printf("    %-24s %9.2f ms/row device time (%lld launches)\n", name.c_str(),
                timing.milliseconds * per_row, (long long)timing.launches);
    if (name == "update_table_row") row_kernel_ms = timing.milliseconds * per_row;
  }
  std::printf("    host-side gap: update %.2f - update_table_row %.2f = %.2f ms/row\n",
              update_ms_per_row, row_kernel_ms, update_ms_per_row - row_kernel_ms);
  for (const auto& [phase, ms] : backend.host_timings())
    std::printf("      host %-34s %7.2f ms/row wall\n", phase.c_str(), ms * per_row);
}

}  // namespace

int main(int argc, char** argv) {
  const bool cases_only = argc > 1 && std::strcmp(argv[1], "--cases") == 0;
  const bool quick = cases_only || (argc > 1 && std::strcmp(argv[1], "--quick") == 0);
  int case_rows = 3;
  std::string save_dir;
  detail::OpenCLRowOptions row_options;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--rows"))
      case_rows = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--group"))
      row_options.group_size = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--per-item"))
      row_options.per_item = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--texels"))
      texels_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--save-texels"))
      save_dir = argv[++i];
  }
  if (!save_dir.empty()) {
    std::filesystem::create_directories(save_dir);
    save_texels(exemplar_texels("chain_199x82.png", 199, 82),
                texels_path(save_dir, "chain_199x82.png"));
    save_texels(exemplar_texels("braid_325x64.png", 325, 64),
                texels_path(save_dir, "braid_325x64.png"));
    return 0;
  }
  tw::set_log_level(spdlog::level::warn);
  std::string why;
  auto context = OpenCLContext::create_default(&why);
  if (!context) {
    std::printf("no OpenCL device: %s\n", why.c_str());
    return 1;
  }
  std::printf("OpenCL device: %s\n", context->device_name().c_str());
  detail::OpenCLBackend opencl(*context, row_options);
  std::printf("row kernel: %d work-items per group, %d positions per work-item\n",
              opencl.row_options().group_size, opencl.row_options().per_item);
  auto cpu = detail::make_cpu_backend();
  {  // first use compiles the kernels (PoCL caches them in ~/.cache/pocl): not timed
    const CostTexels warm = generated_chain(40, 20);
    detail::run_dp(opencl, make_input(warm, 3));
  }

  struct Case {
    const char* file;
    int width, height;
    double paper_ms;
  };
  const Case cases[] = {{"chain_199x82.png", 199, 82, 30.0}, {"braid_325x64.png", 325, 64, 650.0}};
  const int rows = cases_only ? case_rows : quick ? 4 : 10;
  std::printf("\nms per DP row (N = %d pieces, C = H, gentle arc); paper: GTX 580\n", rows + 1);
  for (const Case& c : cases) {
    const CostTexels texels = exemplar_texels(c.file, c.width, c.height);
    const detail::DpInput input = make_input(texels, rows + 1);
    opencl.reset_timings();
    const RowTiming cl = time_dp(opencl, input);
    const RowTiming ref = time_dp(*cpu, input);
    std::printf("  %dx%d C=%d  valid/row %.0f of U=%lld\n", texels.width, texels.height,
                input.space.column, cl.mean_valid, (long long)input.space.count());
    std::printf("    opencl %8.1f ms/row (update %8.1f)  cpu %8.1f ms/row (update %8.1f)\n",
                cl.ms_per_row, cl.update_ms_per_row, ref.ms_per_row, ref.update_ms_per_row);
    std::printf(
        "    paper %6.1f ms/row  opencl/paper %.2fx  cpu/paper %.2fx  opencl/cpu %.2fx  same"
        " optimum: %s\n",
        c.paper_ms, cl.ms_per_row / c.paper_ms, ref.ms_per_row / c.paper_ms,
        cl.ms_per_row / ref.ms_per_row, cl.cost == ref.cost ? "yes" : "NO");
    print_kernel_times(opencl, rows, cl.update_ms_per_row);
  }

  if (cases_only) return 0;
  const CostTexels chain = exemplar_texels("chain_199x82.png", 199, 82);
  std::printf("\ntime vs N (199x82): total ms of the DP rows\n");
  for (int n : quick ? std::vector<int>{2, 4, 8} : std::vector<int>{2, 5, 10, 20, 40}) {
    const detail::DpInput input = make_input(chain, n);
    const RowTiming cl = time_dp(opencl, input);
    const RowTiming ref = time_dp(*cpu, input);
    std::printf("  N=%3d  opencl %9.1f ms  cpu %9.1f ms\n", n, cl.ms_per_row * (n - 1),
                ref.ms_per_row * (n - 1));
  }
  std::printf("\ntime vs W (chain, H = 82, N = %d): ms per row\n", rows + 1);
  for (int w : quick ? std::vector<int>{50, 199} : std::vector<int>{50, 100, 150, 199, 300}) {
    const CostTexels texels = crop(chain, w);
    const detail::DpInput input = make_input(texels, rows + 1);
    const RowTiming cl = time_dp(opencl, input);
    const RowTiming ref = time_dp(*cpu, input);
    std::printf("  W=%3d  valid/row %6.0f  opencl %8.1f ms  cpu %8.1f ms\n", w, cl.mean_valid,
                cl.ms_per_row, ref.ms_per_row);
  }
  return 0;
}
