// The CPU backend of the synthesizer on the paper's workloads: ms per DP row and valid
// positions for exemplars 199x82 and 325x64 (samples/exemplars/), the pruned row against the
// naive exact row, time versus the number of pieces (156x64, C = 90: linear) and versus the
// exemplar width (H = 64, N = 23, C = 90: quadratic), peak memory, and ratios to the paper's
// GTX 580 figures (30 ms and 650 ms per row). Prints numbers only; never fails on time.
//
// usage: bench_synth [--quick] [--pictures DIR] [--rows [REPEATS]] [--objective [REPEATS]]
//   --pictures DIR: write synth_*.png result pictures
//   --rows: replay the recorded DP rows of both exemplars REPEATS times (default 5), CPU against
//           OpenCL (when a device exists) on the same rows: best and median ms per row.
//   --objective: ms per DP row with objective paper and pattern (the unary term's cost), both
//           exemplars, CPU and OpenCL (when a device exists), best of REPEATS (default 3).
#include <OpenImageIO/imageio.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "ribbon/ribbon.hpp"
#include "synth/baseline.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/forwarding_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/opencl_context.hpp"
#include "synth/render.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"

namespace {

using namespace tw;
using Clock = std::chrono::steady_clock;

std::string sample(const std::string& name) {
  return std::string(TERRAWEAVE_SOURCE_DIR) + "/samples/exemplars/" + name;
}

// Process CPU time (every thread: TBB workers, PoCL's), in ms: the machine is shared, so CPU time
// compares where wall time does not.
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

// A gentle arc (radius 400 m) of `pieces` pieces of `delta` m, one texel per metre.
Ribbon arc_ribbon(int pieces, double width, double delta) {
  const double radius = 400.0, length = delta * pieces;
  Curve curve;
  for (int i = 0; i <= 4 * pieces; ++i) {
    const double a = length / radius * i / (4.0 * pieces);
    curve.points.push_back({radius * std::sin(a), radius * (1 - std::cos(a))});
  }
  return make_ribbon(curve, {width, delta});
}

GridSpec canvas_for(const Ribbon& ribbon, double pixel) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Piece& p : ribbon.pieces)
    for (Vec2 v : {p.top_left, p.bottom_left, p.bottom_right, p.top_right}) {
      x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
      y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    }
  GridSpec g;
  g.origin_x = x0 - 2 * pixel;
  g.origin_y = y1 + 2 * pixel;
  g.pixel_width = g.pixel_height = pixel;
  g.width = int(std::ceil((x1 - x0) / pixel)) + 4;
  g.height = int(std::ceil((y1 - y0) / pixel)) + 4;
  return g;
}

Synthesis run(const Exemplar& e, const Ribbon& r, double scale = 1.0) {
  auto backend = detail::make_cpu_backend();
  SynthParams params;
  params.scale = scale;
  params.allow_empty_pieces = true;
  return detail::synthesize_on(*backend, e, r, canvas_for(r, 1.0 / scale), nullptr, params);
}

double mean(const std::vector<int>& v) {
  double s = 0;
  for (int x : v) s += x;
  return v.empty() ? 0 : s / v.size();
}

Exemplar crop(const Exemplar& e, int width) {
  const int n = e.channel_count();
  std::vector<float> t;
  for (int y = 0; y < e.height; ++y)
    t.insert(t.end(), e.texels.begin() + (std::size_t(y) * e.width) * n,
             e.texels.begin() + (std::size_t(y) * e.width + width) * n);
  return make_exemplar(width, e.height, e.channel_names, std::move(t), e.path + " (cropped)");
}

void per_row(const std::string& file, double paper_ms, int pieces, bool naive) {
  const Exemplar e = load_exemplar(sample(file));
  const Ribbon ribbon = arc_ribbon(pieces, 90.0, 12.0);
  const Synthesis s = run(e, ribbon);
  const double row = s.timings.update_ms / std::max(1, s.timings.rows);
  const double other = (s.timings.find_valid_ms + s.timings.compact_ms + s.timings.extract_ms) /
                       std::max(1, s.timings.rows);
  std::printf(
      "%-22s %4dx%-3d C=%d N=%d  valid/piece %7.0f of U=%d (%4.1f %%)  row update %8.1f ms"
      "  other stages %6.1f ms/row  paper %5.0f ms  ratio %.2fx\n",
      file.c_str(), e.width, e.height, s.column, pieces, mean(s.valid_counts),
      e.width * (e.height + s.column),
      100.0 * mean(s.valid_counts) / (e.width * (e.height + s.column)), row, other, paper_ms,
      row / paper_ms);
  if (!naive) return;
  // One naive exact row (every pair, every sample) on the same columns, for the speed-up.
  detail::ColumnSet right, left;
  auto backend = detail::make_cpu_backend();
  detail::PositionSpace space{e.width, e.height, s.column};
  const auto fp =
      detail::make_piece_footprint(ribbon.pieces[0], 1.0, s.column, GridSpec{}, nullptr);
  std::vector<std::uint8_t> flags;
  std::vector<std::int32_t> idx;
  backend->find_valid_positions(e.cost, space, fp, flags);
  backend->compact_valid_positions(flags, idx);
  backend->extract_right_columns(e.cost, space, fp, idx, right);
  backend->extract_left_columns(e.cost, space, idx, left);
  std::vector<std::int64_t> previous(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) previous[i] = std::int64_t((i * 7919) % 50000);
  std::vector<std::int64_t> c1, c2;
  std::vector<std::int32_t> a1, a2;
  auto t0 = Clock::now();
  std::int64_t evaluated = 0;
  detail::update_table_row_pruned(previous, right, left, c1, a1, &evaluated);
  const double pruned_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  t0 = Clock::now();
  detail::update_table_row_naive(previous, right, left, c2, a2);
  const double naive_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  std::printf(
      "  synthetic row V=%zu: pruned %.1f ms (%.3f %% of pairs fully evaluated), naive %.1f"
      " ms, speed-up %.1fx, identical: %s\n",
      idx.size(), pruned_ms, 100.0 * evaluated / (double(idx.size()) * idx.size()), naive_ms,
      naive_ms / pruned_ms, (c1 == c2 && a1 == a2) ? "yes" : "NO");
}

// Records the inputs of every DP row of a synthesis so that the row update can be replayed and
// timed alone, repeatedly, on the very same rows (the machine is shared: best and median).
class RecordingBackend final : public detail::ForwardingBackend {
 public:
  struct Row {
    std::vector<std::int64_t> previous;
    detail::ColumnSet right, left;
  };
  std::vector<Row> rows;

  std::string name() const override { return "recording cpu"; }
  void update_table_row(const std::vector<std::int64_t>& previous, const detail::ColumnSet& right,
                        const detail::ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override {
    rows.push_back({previous, right, left});
    ForwardingBackend::update_table_row(previous, right, left, cost, argmin);
  }
};

struct Spread {
  double best = 0, median = 0;
};
Spread spread_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? Spread{} : Spread{v.front(), v[v.size() / 2]};
}

// ms per row update, CPU (pruned) against OpenCL (when a device exists) on the same recorded
// rows: best and median over `repeats` passes, pairs fully evaluated, identical results.
void replay_rows(const std::string& file, double paper_ms, int pieces, int repeats,
                 detail::Backend* opencl, Objective objective) {
  const Exemplar e = load_exemplar(sample(file));
  const Ribbon ribbon = arc_ribbon(pieces, 90.0, 12.0);
  RecordingBackend recorder;
  SynthParams params;
  params.scale = 1.0;
  params.allow_empty_pieces = true;
  params.objective = objective;
  const Synthesis s =
      detail::synthesize_on(recorder, e, ribbon, canvas_for(ribbon, 1.0), nullptr, params);
  const double per_row = 1.0 / std::max(1, s.timings.rows);
  std::vector<double> cpu_ms, cl_ms, cpu_cpu_ms, cl_cpu_ms;
  double pairs = 0, evaluated = 0;
  bool identical = true;
  for (int pass = 0; pass < repeats; ++pass) {
    double cpu_total = 0, cl_total = 0, cpu_cpu = 0, cl_cpu = 0;
    for (const RecordingBackend::Row& row : recorder.rows) {
      std::vector<std::int64_t> cost, cl_cost;
      std::vector<std::int32_t> argmin, cl_argmin;
      std::int64_t count = 0;
      auto t0 = Clock::now();
      double c0 = process_cpu_ms();
      detail::update_table_row_pruned(row.previous, row.right, row.left, cost, argmin, &count);
      cpu_total += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      cpu_cpu += process_cpu_ms() - c0;
      if (pass == 0) {
        evaluated += double(count);
        pairs += double(row.previous.size()) * double(cost.size());
      }
      if (!opencl) continue;
      t0 = Clock::now();
      c0 = process_cpu_ms();
      opencl->update_table_row(row.previous, row.right, row.left, cl_cost, cl_argmin);
      cl_total += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      cl_cpu += process_cpu_ms() - c0;
      identical = identical && cost == cl_cost && argmin == cl_argmin;
    }
    const double rows = std::max<std::size_t>(1, recorder.rows.size());
    cpu_ms.push_back(cpu_total / rows);
    cl_ms.push_back(cl_total / rows);
    cpu_cpu_ms.push_back(cpu_cpu / rows);
    cl_cpu_ms.push_back(cl_cpu / rows);
  }
  const Spread cpu = spread_of(cpu_ms), cl = spread_of(cl_ms);
  const Spread cpu_cpu = spread_of(cpu_cpu_ms), cl_cpu = spread_of(cl_cpu_ms);
  std::printf(
      "%-17s %-7s %dx%d C=%d rows=%zu valid/piece %6.0f  row update ms: cpu best %6.1f median "
      "%6.1f (CPU-ms %6.1f / %6.1f)",
      file.c_str(), objective == Objective::paper ? "paper" : "pattern", e.width, e.height,
      s.column, recorder.rows.size(), mean(s.valid_counts), cpu.best, cpu.median, cpu_cpu.best,
      cpu_cpu.median);
  if (opencl)
    std::printf(" | opencl best %6.1f median %6.1f (CPU-ms %6.1f / %6.1f; same results: %s)",
                cl.best, cl.median, cl_cpu.best, cl_cpu.median, identical ? "yes" : "NO");
  std::printf(
      " | paper %.0f | fully evaluated %.4f %% of pairs | per row: find valid %.1f, compact %.1f,"
      " extract %.1f ms (cpu)\n",
      paper_ms, 100.0 * evaluated / std::max(1.0, pairs), s.timings.find_valid_ms * per_row,
      s.timings.compact_ms * per_row, s.timings.extract_ms * per_row);
}

void write_png(const std::string& path, int w, int h, const std::vector<std::uint8_t>& rgba) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return;
  out->open(path, OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8));
  out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
  out->close();
}

// The result over a light background, the ribbon cage in red (the paper's Figure 2).
void picture(const Exemplar& e, const std::string& shape, double size, double width, double delta,
             const std::string& path, bool parametric = false) {
  const Ribbon ribbon = make_ribbon(make_shape(shape, size), {width, delta});
  const GridSpec canvas = canvas_for(ribbon, 1.0);
  const Synthesis s = parametric ? parametric_baseline(e, ribbon, 1.0) : run(e, ribbon);
  const Window all = Window::whole(canvas);
  const RenderedPattern p = render_pattern(e, ribbon, s, canvas, all, !parametric);
  const Raster<float> cage = render_cage(ribbon, canvas, all);
  std::vector<std::uint8_t> rgba(std::size_t(all.width) * all.height * 4);
  for (int y = 0; y < all.height; ++y)
    for (int x = 0; x < all.width; ++x) {
      const float a = p.coverage.at(x, y);
      std::uint8_t* px = rgba.data() + (std::size_t(y) * all.width + x) * 4;
      for (int c = 0; c < 3; ++c) {
        float v = 0.95f * (1 - a) + p.channels[std::size_t(c)].at(x, y) * a;
        if (cage.at(x, y) > 0) v = c == 0 ? 0.9f : 0.3f * v + 0.1f;
        px[c] = std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
      }
      px[3] = 255;
    }
  write_png(path, all.width, all.height, rgba);
  std::printf("picture %s: %s, %zu pieces, mean seam %.1f -> stitched %.1f\n", path.c_str(),
              shape.c_str(), ribbon.pieces.size(), s.mean_seam_cost, s.mean_seam_cost_stitched);
}

}  // namespace

// The cost of the pattern objective's unary term: whole syntheses along the arc with objective
// paper and pattern (the same coverage floor), best of `repeats`, ms per DP row of the row
// update alone and of the whole synthesis (find valid, unary costs, extraction, update,
// backtracking, stitching), on the CPU backend and on OpenCL when a device exists.
void objective_cost(const std::string& file, int pieces, int repeats, detail::Backend* opencl) {
  const Exemplar e = load_exemplar(sample(file));
  const Ribbon ribbon = arc_ribbon(pieces, 90.0, 12.0);
  auto cpu = detail::make_cpu_backend();
  for (detail::Backend* backend : {cpu.get(), opencl}) {
    if (!backend) continue;
    double update[2] = {1e300, 1e300}, whole[2] = {1e300, 1e300};
    std::vector<double> cpu[2];
    SynthTimings stages[2];
    std::int64_t omega[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      SynthParams params;
      params.scale = 1.0;
      params.allow_empty_pieces = true;
      params.objective = k == 0 ? Objective::paper : Objective::pattern;
      for (int pass = 0; pass < repeats; ++pass) {
        const double cpu0 = process_cpu_ms();
        const Synthesis s =
            detail::synthesize_on(*backend, e, ribbon, canvas_for(ribbon, 1.0), nullptr, params);
        const double rows = std::max(1, s.timings.rows);
        cpu[k].push_back((process_cpu_ms() - cpu0) / rows);
        if (s.timings.update_ms / rows < update[k]) stages[k] = s.timings;
        update[k] = std::min(update[k], s.timings.update_ms / rows);
        whole[k] = std::min(whole[k], s.timings.total_ms / rows);
        omega[k] = s.total_cost;
      }
    }
    std::printf(
        "%-17s %-6s N=%d  ms per DP row, best of %d: row update paper %7.1f pattern %7.1f "
        "(ratio %.2fx) | whole synthesis paper %7.1f pattern %7.1f (ratio %.2fx) | Omega %lld / "
        "%lld\n",
        file.c_str(), backend->name().c_str(), pieces, repeats, update[0], update[1],
        update[1] / update[0], whole[0], whole[1], whole[1] / whole[0], (long long)omega[0],
        (long long)omega[1]);
    const Spread paper = spread_of(cpu[0]), pattern = spread_of(cpu[1]);
    std::printf(
        "%-17s %-6s N=%d  CPU-ms per DP row (whole synthesis, all threads), best / median of %d: "
        "paper %7.1f / %7.1f  pattern %7.1f / %7.1f (ratio of bests %.2fx)\n",
        file.c_str(), backend->name().c_str(), pieces, repeats, paper.best, paper.median,
        pattern.best, pattern.median, pattern.best / paper.best);
    for (int k = 0; k < 2; ++k) {
      const SynthTimings& t = stages[k];
      const double rows = std::max(1, t.rows);
      std::printf(
          "  %s stages, wall ms per row: footprints %.1f find valid %.1f compact %.1f extract %.1f "
          "update %.1f backtrack %.1f stitch %.1f rest %.1f\n",
          k == 0 ? "paper  " : "pattern", t.footprints_ms / rows, t.find_valid_ms / rows,
          t.compact_ms / rows, t.extract_ms / rows, t.update_ms / rows, t.backtrack_ms / rows,
          t.stitch_ms / rows,
          (t.total_ms - t.footprints_ms - t.find_valid_ms - t.compact_ms - t.extract_ms -
           t.update_ms - t.backtrack_ms - t.stitch_ms) /
              rows);
    }
  }
}

int main(int argc, char** argv) {
  bool quick = false;
  std::string pictures;
  int rows = 0, objective = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--objective"))
      objective = i + 1 < argc && std::isdigit(argv[i + 1][0]) ? std::atoi(argv[++i]) : 3;
    if (!std::strcmp(argv[i], "--rows"))
      rows = i + 1 < argc && std::isdigit(argv[i + 1][0]) ? std::atoi(argv[++i]) : 5;
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    if (!std::strcmp(argv[i], "--pictures") && i + 1 < argc) pictures = argv[++i];
  }
  if (rows > 0 || objective > 0) {
    std::string why;
    auto context = OpenCLContext::create_default(&why);
    std::unique_ptr<detail::Backend> opencl;
    if (context) {
      opencl = std::make_unique<detail::OpenCLBackend>(*context);
      std::printf("OpenCL device: %s\n", context->device_name().c_str());
      std::vector<std::int64_t> c;
      std::vector<std::int32_t> a;
      opencl->update_table_row({0}, {1, {0u}, true}, {1, {0u}, true}, c, a);  // build kernels
    } else {
      std::printf("no OpenCL device (%s): CPU only\n", why.c_str());
    }
    if (objective > 0) {
      objective_cost("chain_199x82.png", 9, objective, opencl.get());
      objective_cost("braid_325x64.png", 5, objective, opencl.get());
      return 0;
    }
    for (Objective objective : {Objective::paper, Objective::pattern}) {
      replay_rows("chain_199x82.png", 30.0, 9, rows, opencl.get(), objective);
      replay_rows("braid_325x64.png", 650.0, 5, rows, opencl.get(), objective);
    }
    return 0;
  }
  if (!pictures.empty()) {
    const Exemplar chain = load_exemplar(sample("chain_199x82.png"));
    picture(chain, "s-curve", 500, 90, 40, pictures + "/synth_chain_scurve.png");
    picture(chain, "heart", 500, 90, 40, pictures + "/synth_chain_heart.png");
    picture(chain, "hairpin", 500, 90, 40, pictures + "/synth_chain_hairpin.png");
    picture(chain, "s-curve", 500, 90, 40, pictures + "/synth_chain_scurve_parametric.png", true);
    return 0;
  }
  std::printf(
      "CPU backend, %d pieces per exemplar row test (1 texel per metre, C = 90, delta = 12)\n",
      quick ? 4 : 8);
  per_row("chain_199x82.png", 30.0, quick ? 4 : 8, !quick);
  per_row("braid_325x64.png", 650.0, quick ? 3 : 6, false);

  std::printf("\ntime vs number of pieces (zigzag 156x64, C = 90, delta = 12): expected linear\n");
  const Exemplar zigzag = load_exemplar(sample("zigzag_156x64.png"));
  for (int n : quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 20, 40}) {
    const Synthesis s = run(zigzag, arc_ribbon(n, 90.0, 12.0));
    std::printf("  N=%3d  total %8.1f ms  DP rows %8.1f ms  (%.1f ms/row)\n", n, s.timings.total_ms,
                s.timings.update_ms, s.timings.update_ms / std::max(1, s.timings.rows));
  }
  std::printf(
      "\ntime vs exemplar width (braid cropped, H = 64, N = 23, C = 90): expected quadratic\n");
  const Exemplar braid = load_exemplar(sample("braid_325x64.png"));
  for (int w : quick ? std::vector<int>{80, 160} : std::vector<int>{80, 160, 240, 325}) {
    const Synthesis s = run(crop(braid, w), arc_ribbon(23, 90.0, 12.0));
    std::printf("  W=%3d  valid/piece %6.0f  total %8.1f ms  DP rows %8.1f ms\n", w,
                mean(s.valid_counts), s.timings.total_ms, s.timings.update_ms);
  }
  std::printf("\npeak memory (max RSS): %.1f MB\n", peak_rss_mb());
  return 0;
}
