// Default synthesis quality (issue #11) and the cost of the pattern objective.
//   bench_quality                         the table of docs/synthesis.md: every exemplar of
//                                         samples/exemplars x S-curve, hairpin, circle, default
//                                         parameters, paper objective vs pattern objective
//   bench_quality --write-exemplars DIR   writes the generated exemplars (gen_*.png)
//   bench_quality --pictures DIR          before/after PNGs (paper vs pattern) into DIR
// Prints numbers; never fails on time.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "commands/synth_command.hpp"
#include "generated_exemplars.hpp"
#include "synth/baseline.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"

namespace fs = std::filesystem;
using namespace tw;

namespace {

// Built-in curves at the ribbon's scale, as in tests/synth/test_default_quality.cpp: the
// S-curve's arcs have radius 1 width, the circle's 2, the hairpin's legs lie 1.2 widths apart.
double shape_length(const std::string& shape, double width) {
  return shape == "hairpin" ? 10.0 * width : 4.0 * width;
}

const fs::path kExemplars = fs::path(TERRAWEAVE_SOURCE_DIR) / "samples/exemplars";

void write_exemplars(const fs::path& dir) {
  fs::create_directories(dir);
  for (const auto& g : test::generated_exemplars()) {
    const Exemplar& e = g.exemplar;
    std::vector<unsigned char> rgba(std::size_t(e.width) * e.height * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
      rgba[i] = (unsigned char)std::lround(std::clamp(e.texels[i], 0.0f, 1.0f) * 255.0f);
    const std::string path = (dir / (g.name + ".png")).string();
    auto out = OIIO::ImageOutput::create(path);
    const OIIO::ImageSpec spec(e.width, e.height, 4, OIIO::TypeDesc::UINT8);
    if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) ||
        !out->close()) {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      std::exit(1);
    }
    std::printf("wrote %s\n", path.c_str());
  }
}

GridSpec canvas_for(const Ribbon& ribbon, double margin) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Piece& p : ribbon.pieces)
    for (Vec2 v : {p.top_left, p.bottom_left, p.bottom_right, p.top_right})
      x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y),
      y1 = std::max(y1, v.y);
  GridSpec g;
  g.origin_x = x0 - margin, g.origin_y = y1 + margin;
  g.pixel_width = g.pixel_height = 1.0;
  g.width = int(std::ceil(x1 - x0 + 2 * margin)), g.height = int(std::ceil(y1 - y0 + 2 * margin));
  return g;
}

// The same cases as tests/synth/test_default_quality.cpp.
void table() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kExemplars))
    if (entry.path().extension() == ".png") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::printf(
      "| exemplar | curve | N | coverage ratio paper / pattern | seam stitched paper / pattern / "
      "parametric | DP row update ms paper / pattern | s paper / pattern | properties |\n"
      "|---|---|---|---|---|---|---|---|\n");
  int cases = 0, passed = 0;
  double update_paper = 0, update_pattern = 0;
  int rows_paper = 0, rows_pattern = 0;
  for (const fs::path& file : files) {
    const Exemplar exemplar = load_exemplar(file.string());
    const ExemplarStats stats = exemplar_stats(exemplar);
    const double width = suggested_width(stats, 1.0);
    for (const char* shape : {"s-curve", "hairpin", "circle"}) {
      const Ribbon ribbon = make_ribbon(make_shape(shape, shape_length(shape, width)),
                                        {width, suggested_delta(stats, 1.0)});
      const GridSpec canvas = canvas_for(ribbon, 4.0);
      auto cpu = detail::make_cpu_backend();
      Synthesis result[2];
      std::string error[2];
      for (int k = 0; k < 2; ++k) {
        SynthParams params;
        params.scale = 1.0;
        params.objective = k == 0 ? Objective::paper : Objective::pattern;
        if (k == 0) params.min_coverage = 0.0;  // the paper as it was: no floor
        try {
          result[k] = detail::synthesize_on(*cpu, exemplar, ribbon, canvas, nullptr, params);
        } catch (const std::exception& e) {
          error[k] = e.what();
        }
      }
      const Synthesis base = parametric_baseline(exemplar, ribbon, 1.0);
      update_paper += result[0].timings.update_ms, rows_paper += result[0].timings.rows;
      update_pattern += result[1].timings.update_ms, rows_pattern += result[1].timings.rows;
      auto cell = [&](int k, double v) {
        return error[k].empty() ? fmt::format("{:.2f}", v) : std::string("failed");
      };
      // The properties of the default-quality test, on the whole exemplar (pattern objective).
      std::string failed;
      if (!error[1].empty())
        failed = "run fails";
      else if (result[1].coverage_ratio < 0.8)
        failed = "coverage < 0.8";
      else if (!(result[1].mean_seam_cost_stitched < base.mean_seam_cost))
        failed = "seam";
      ++cases, passed += failed.empty();
      std::printf(
          "| %s | %s | %zu | %s / **%s** | %s / **%s** / %.1f | %.1f / %.1f | %.2f / %.2f | %s |\n",
          file.stem().c_str(), shape, ribbon.pieces.size(),
          cell(0, result[0].coverage_ratio).c_str(), cell(1, result[1].coverage_ratio).c_str(),
          cell(0, result[0].mean_seam_cost_stitched).c_str(),
          cell(1, result[1].mean_seam_cost_stitched).c_str(), base.mean_seam_cost,
          result[0].timings.rows ? result[0].timings.update_ms / result[0].timings.rows : 0.0,
          result[1].timings.rows ? result[1].timings.update_ms / result[1].timings.rows : 0.0,
          result[0].timings.total_ms / 1000.0, result[1].timings.total_ms / 1000.0,
          failed.empty() ? "ok" : failed.c_str());
      for (int k = 0; k < 2; ++k)
        if (!error[k].empty()) std::printf("<!-- %s -->\n", error[k].c_str());
    }
  }
  std::printf(
      "\nDefault quality on the whole exemplars: %d of %d cases hold all three properties\n",
      passed, cases);
  std::printf(
      "\nDP row update (unary term included) over all cases: paper %.2f ms per row (%d rows), "
      "pattern %.2f ms per row (%d rows), ratio %.3f\n",
      update_paper / std::max(1, rows_paper), rows_paper,
      update_pattern / std::max(1, rows_pattern), rows_pattern,
      (update_pattern / std::max(1, rows_pattern)) / (update_paper / std::max(1, rows_paper)));
}

// Before (paper objective, no floor) / after (defaults) pictures through `terraweave synth`'s code.
void pictures(const fs::path& dir) {
  fs::create_directories(dir);
  struct Case {
    const char* exemplar;
    const char* shape;
  };
  for (const Case c :
       {Case{"ridge_band_200x64.png", "s-curve"}, Case{"rock_band_260x80.png", "s-curve"},
        Case{"gen_holes_160x48.png", "circle"}}) {
    const Exemplar exemplar = load_exemplar((kExemplars / c.exemplar).string());
    const double width = suggested_width(exemplar_stats(exemplar), 1.0);
    for (int k = 0; k < 2; ++k) {
      SynthCommand command;
      command.exemplar = kExemplars / c.exemplar;
      command.curve = c.shape;
      command.length = shape_length(c.shape, width);
      command.scale = 1.0;
      command.objective = k == 0 ? Objective::paper : Objective::pattern;
      if (k == 0) command.min_coverage = 0.0;
      command.output =
          dir / fmt::format("objective_{}_{}_{}.png", fs::path(c.exemplar).stem().string(), c.shape,
                            k == 0 ? "paper" : "pattern");
      const Synthesis s = run_synth_command(command);
      std::printf("%s: coverage ratio %.3f, seam %.1f\n", command.output.c_str(), s.coverage_ratio,
                  s.mean_seam_cost);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--write-exemplars") == 0) {
    write_exemplars(argv[2]);
  } else if (argc == 3 && std::strcmp(argv[1], "--pictures") == 0) {
    pictures(argv[2]);
  } else if (argc == 1) {
    table();
  } else {
    std::fprintf(stderr, "usage: bench_quality [--write-exemplars DIR | --pictures DIR]\n");
    return 2;
  }
  return 0;
}
