#pragma once
// SplitMix64 as a small generator: the same draws on every platform from the same seed
// (std:: distributions are implementation-defined). Header-only, no state but its own.
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tw {

class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}
  constexpr std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  // [0, n): n > 0
  std::uint64_t below(std::uint64_t n) { return next() % n; }
  // A standard normal draw (Box-Muller, one of the pair): two uniform draws.
  double normal() {
    const double u = 1.0 - uniform(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
  }

 private:
  std::uint64_t state_;
};

// One draw from a generator seeded with x: a hash of x that mixes every bit (seeds derived
// from several values: `split_mix64(split_mix64(a) ^ b)`).
constexpr std::uint64_t split_mix64(std::uint64_t x) {
  return SplitMix64(x).next();
}

// The seed of one feature (FID) of a class in a run, for every synthesis method (the curve
// patterns, the areas' shape-patterns): split_mix64 over (run seed, class seed, FID), never 0
// (0 would ask a synthesizer for its seedless global optimum).
constexpr std::uint64_t feature_seed(std::uint64_t run_seed, std::uint64_t class_seed,
                                     std::int64_t fid) {
  std::uint64_t h = split_mix64(run_seed);
  h = split_mix64(h ^ class_seed);
  h = split_mix64(h ^ std::uint64_t(fid));
  return h == 0 ? 1 : h;
}

}  // namespace tw
