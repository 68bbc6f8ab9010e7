// Growth time and peak memory against the region's area (docs/networks.md, "Speed"): the bocage
// exemplar (hedged fields of ~0.7 ha, hedgerow density) grown over square regions of 1.25, 2.5,
// 5, 10 and 40 km², each in a child process so that its peak RSS is its own. Single-threaded (the
// growth is sequential and deterministic).
//   build/bench/bench_network_speed
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"

using namespace tw;

int main() {
  std::printf(
      "| region | nodes | edges | growth s | check s | peak RSS MB |\n|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (double km2 : {1.25, 2.5, 5.0, 10.0, 40.0}) {
    const pid_t pid = fork();
    if (pid == 0) {
      Warnings warnings;
      const Network ex =
          build_planar_network(example_network("bocage", 800.0, 3), 1e-3, "bocage", warnings);
      const double side = std::sqrt(km2) * 1000.0;
      const std::vector<Polygon> region{{{{0, 0}, {side, 0}, {side, side}, {0, side}}}};
      const auto t0 = std::chrono::steady_clock::now();
      const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = 1});
      const auto t1 = std::chrono::steady_clock::now();
      const NetworkCheck check = check_network(out, region, nullptr);
      const auto t2 = std::chrono::steady_clock::now();
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      std::printf("| %.2f km² | %zu | %zu | %.2f | %.2f | %.0f |%s\n", km2, out.nodes.size(),
                  out.edges.size(), std::chrono::duration<double>(t1 - t0).count(),
                  std::chrono::duration<double>(t2 - t1).count(), usage.ru_maxrss / 1024.0,
                  check.total() ? " CHECK FAILED" : "");
      std::fflush(stdout);
      _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
  }
}
