// The quality table of docs/networks.md: for eight exemplars (six synthetic kinds, the county
// boundaries of North Carolina from r-cran-sf, one drawn SVG), each style property's normalized
// Wasserstein-1 distance between the exemplar and (a) the grown output, (b) the exemplar's other
// half, (c) the naive baseline (random exemplar patches), and the dangling ends per km; writes
// docs/images/network_<name>.png (exemplar | output | baseline) with --images DIR.
//   build/bench/bench_network_quality [--images docs/images] [--seed N]
//                                     [--method automatic|growth|quilt|layout]
// NETWORK_VERBOSE=1 also prints, per exemplar, degree histograms, bent edges, mean lengths and
// areas of the exemplar, the output and the baseline, and the growth counters.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/atomic_output.hpp"
#include "network/baseline.hpp"
#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/preview.hpp"
#include "network/stats.hpp"

using namespace tw;

namespace {

struct Case {
  std::string name;
  NetworkLines lines;
};

std::vector<Polygon> box_of(const Network& n, double factor) {
  const NodeExtent extent = node_extent(n);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const Vec2 c = 0.5 * (lo + hi), h = 0.5 * factor * (hi - lo);
  return {{{{c.x - h.x, c.y - h.y},
            {c.x + h.x, c.y - h.y},
            {c.x + h.x, c.y + h.y},
            {c.x - h.x, c.y + h.y}}}};
}

}  // namespace

int main(int argc, char** argv) {
  std::string images;
  std::uint64_t seed = 1;
  NetworkMethod method = NetworkMethod::automatic;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--method")) {
      if (std::find(kNetworkMethodNames.begin(), kNetworkMethodNames.end(), argv[i + 1]) ==
          kNetworkMethodNames.end()) {
        std::fprintf(stderr, "--method %s: expected automatic, growth, quilt or layout\n",
                     argv[i + 1]);
        return 2;
      }
      method = network_method_named(argv[i + 1]);
    }
    if (!std::strcmp(argv[i], "--images")) images = argv[i + 1];
    if (!std::strcmp(argv[i], "--seed")) seed = std::stoull(argv[i + 1]);
  }
  std::vector<Case> cases;
  for (const char* kind : kExampleNetworks)
    cases.push_back({kind, example_network(kind, 800.0, 3)});
  Warnings warnings;
  const std::string nc = std::string(TERRAWEAVE_SOURCE_DIR) + "/tests/data/nc_counties.geojson";
  cases.push_back({"nc_counties", read_network_lines({.source = nc}, warnings)});
  cases.push_back({"drawn_svg", read_network_lines({.source = std::string(TERRAWEAVE_SOURCE_DIR) +
                                                              "/tests/data/network_drawn.svg"},
                                                   warnings)});
  std::printf(
      "| exemplar | property | output | halves | baseline | target met | tiling "
      "|\n|---|---|---|---|---|---|---|\n");
  int passed = 0, total = 0;
  for (Case& c : cases) {
    const Network ex = build_planar_network(c.lines, 1e-3, c.name, warnings);
    const std::vector<Polygon> region = box_of(ex, 1.0);
    const auto t0 = std::chrono::steady_clock::now();
    NetworkGrowthReport report;
    const Network out =
        grow_network(ex, region, nullptr, nullptr, {.seed = seed, .method = method}, &report);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const Network base = baseline_network(ex, region, seed);
    const Network tiled = baseline_network(ex, region, seed, BaselineKind::tiling);
    const NetworkCheck check = check_network(out, region, nullptr);
    const NetworkStats se = network_stats(ex), so = network_stats(out), sb = network_stats(base),
                       st = network_stats(tiled);
    const auto [ha, hb] = halves(ex);
    const NetworkStats s1 = network_stats(ex, ha), s2 = network_stats(ex, hb);
    if (std::getenv("NETWORK_VERBOSE")) {
      for (const auto* st : {&se, &so, &sb}) {
        int bent = 0;
        for (double c : st->curvature) bent += c > 1e-4;
        std::fprintf(stderr, "  bent %d of %zu\n", bent, st->curvature.size());
        int h[8] = {};
        for (double d : st->degree) h[std::min(7, int(d))]++;
        double ml = 0;
        for (double l : st->edge_length) ml += l / st->edge_length.size();
        double fa = 0;
        for (double a : st->face_area) fa += a / st->face_area.size();
        std::fprintf(stderr,
                     "  deg 1:%d 2:%d 3:%d 4:%d 5+:%d  mean len %.1f  faces %zu mean %.0f\n", h[1],
                     h[2], h[3], h[4], h[5] + h[6] + h[7], ml, st->face_area.size(), fa);
      }
      std::fprintf(stderr,
                   "  placed %d stubs %d seeds %d T %d snapped %d boundary %d rej cross %d region "
                   "%d pruned %d\n",
                   report.placed, report.stubs, report.seeds, report.t_junctions, report.snapped,
                   report.boundary_ends, report.rejected_crossing, report.rejected_region,
                   report.pruned);
    }
    for (int p = 0; p < 6; ++p) {
      const double d_out = normalized_w1(property(se, p), property(so, p));
      const double d_half = normalized_w1(property(s1, p), property(s2, p));
      const double d_base = normalized_w1(property(se, p), property(sb, p));
      const double d_tiled = normalized_w1(property(se, p), property(st, p));
      const bool ok = d_out <= std::max(1.5 * d_half, 0.05) && d_out < d_base;
      passed += ok, ++total;
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %s | %.3f |\n", c.name.c_str(),
                  kNetworkProperties[p], d_out, d_half, d_base, ok ? "yes" : "no", d_tiled);
    }
    const bool ok = so.dangling_per_km() <= 1.5 * se.dangling_per_km() + 1e-9;
    passed += ok, ++total;
    std::printf("| %s | dangling ends per km | %.2f | %.2f (exemplar) | %.2f | %s | %.2f |\n",
                c.name.c_str(), so.dangling_per_km(), se.dangling_per_km(), sb.dangling_per_km(),
                ok ? "yes" : "no", st.dangling_per_km());
    std::fprintf(
        stderr,
        "%s (%s): %zu exemplar edges, %zu output edges in %.0f ms, crossings %lld outside %lld\n",
        c.name.c_str(),
        method == NetworkMethod::automatic
            ? (report.quilted    ? "automatic: quilt"
               : report.laid_out ? "automatic: layout"
                                 : "automatic: growth")
            : std::string(kNetworkMethodNames[std::size_t(method)]).c_str(),
        ex.edges.size(), out.edges.size(), ms, (long long)check.crossings,
        (long long)check.outside);
    if (!images.empty()) {
      OutputTransaction t;
      const auto ex_region = box_of(ex, 1.0);
      write_network_png(t.stage(std::filesystem::path(images) / ("network_" + c.name + ".png")),
                        {{ex_region, {{&ex, {60, 60, 60}, 1.5}}},
                         {region, {{&out, {30, 110, 40}, 1.5}}},
                         {region, {{&base, {150, 60, 40}, 1.5}}}},
                        420);
      t.commit();
    }
  }
  std::printf("\n%d of %d targets met\n", passed, total);
}
