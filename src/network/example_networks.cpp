#include "network/example_networks.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "core/error.hpp"
#include "core/split_mix.hpp"

namespace tw {

namespace {

constexpr double kPi = std::numbers::pi;

// A gently wavy line from a to b (n segments, amplitude across).
std::vector<Vec2> wavy(Vec2 a, Vec2 b, double amplitude, SplitMix64& rng, int n = 8) {
  const Vec2 across = perp(normalized(b - a));
  const double phase = rng.uniform(0, 2 * kPi), waves = rng.uniform(0.5, 1.5);
  std::vector<Vec2> pts;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    const double off = (i == 0 || i == n)
                           ? 0.0
                           : amplitude * std::sin(phase + waves * 2 * kPi * t) * std::sin(kPi * t);
    pts.push_back(lerp(a, b, t) + across * off);
  }
  return pts;
}

void add(NetworkLines& out, std::vector<Vec2> line) {
  out.fids.push_back(std::int64_t(out.lines.size()));
  out.lines.push_back(std::move(line));
}

void grid(NetworkLines& out, double size, SplitMix64& rng) {
  const double dx = 110.0, dy = 80.0;
  const int nx = int(size / dx), ny = int(size / dy);
  std::vector<double> xs;
  for (int i = 0; i <= nx; ++i)
    xs.push_back(i * dx + (i == 0 || i == nx ? 0.0 : rng.uniform(-15, 15)));
  for (double x : xs) add(out, {{x, 0.0}, {x, ny * dy}});
  for (int j = 0; j <= ny; ++j) {
    if (j == 0 || j == ny) {
      add(out, {{0.0, j * dy}, {xs.back(), j * dy}});
      continue;
    }
    for (int i = 0; i < nx; ++i) {  // field boundaries: some strips are undivided
      if (rng.uniform() < 0.25) continue;
      const double y = j * dy + rng.uniform(-12, 12);
      add(out, {{xs[std::size_t(i)], y}, {xs[std::size_t(i) + 1], y}});
    }
  }
}

// Cells split recursively by wavy chords: irregular fields with T-junctions.
void split_cells(NetworkLines& out, double size, SplitMix64& rng, double min_area, double wave) {
  std::function<void(std::vector<Vec2>)> split = [&](std::vector<Vec2> cell) {
    double area = 0.0;
    for (std::size_t i = 0; i < cell.size(); ++i)
      area += cross(cell[i], cell[(i + 1) % cell.size()]);
    area = std::abs(area) / 2;
    // The longest side and the side opposite it are joined by a chord.
    std::size_t longest = 0;
    double best = 0.0;
    for (std::size_t i = 0; i < cell.size(); ++i) {
      const double l = distance(cell[i], cell[(i + 1) % cell.size()]);
      if (l > best) best = l, longest = i;
    }
    if (area < min_area * rng.uniform(0.6, 1.6) || cell.size() > 9) {
      std::vector<Vec2> ring = cell;
      ring.push_back(cell.front());
      add(out, std::move(ring));
      return;
    }
    const std::size_t n = cell.size();
    const std::size_t opposite = (longest + n / 2) % n;
    const double t1 = rng.uniform(0.35, 0.65), t2 = rng.uniform(0.35, 0.65);
    const Vec2 p = lerp(cell[longest], cell[(longest + 1) % n], t1);
    const Vec2 q = lerp(cell[opposite], cell[(opposite + 1) % n], t2);
    std::vector<Vec2> a{p}, b{q};
    for (std::size_t i = (longest + 1) % n;; i = (i + 1) % n) {
      a.push_back(cell[i]);
      if (i == opposite) break;
    }
    a.push_back(q);
    for (std::size_t i = (opposite + 1) % n;; i = (i + 1) % n) {
      b.push_back(cell[i]);
      if (i == longest) break;
    }
    b.push_back(p);
    // The chord itself, wavy (a hedge), drawn once; the cells' rings keep it straight, so the
    // rings are not drawn: only chords and the outer square.
    add(out, wavy(p, q, wave * distance(p, q), rng));
    split(a), split(b);
  };
  std::vector<Vec2> square{{0, 0}, {size, 0}, {size, size}, {0, size}};
  add(out, {square[0], square[1], square[2], square[3], square[0]});
  // Splitting on straight chords keeps later chords' ends on the earlier (straight) ones; the
  // wavy drawing of a chord is its own line, so only straight chords are drawn when wave = 0.
  split(square);
}

void drainage(NetworkLines& out, double size, SplitMix64& rng) {
  std::function<void(Vec2, double, double, int)> branch = [&](Vec2 at, double heading,
                                                              double length, int depth) {
    std::vector<Vec2> line{at};
    Vec2 p = at;
    double h = heading;
    const int steps = 6;
    for (int i = 0; i < steps; ++i) {
      h += rng.uniform(-0.15, 0.15);
      p = p + Vec2{std::cos(h), std::sin(h)} * (length / steps);
      line.push_back(p);
    }
    add(out, line);
    if (depth == 0) return;
    const double spread = rng.uniform(0.45, 0.8);
    branch(p, h + spread, length * rng.uniform(0.6, 0.85), depth - 1);
    branch(p, h - spread * rng.uniform(0.6, 1.2), length * rng.uniform(0.6, 0.85), depth - 1);
  };
  for (int k = 0; k < 3; ++k)
    branch({size * (0.2 + 0.3 * k), 0.0}, kPi / 2 + rng.uniform(-0.2, 0.2), size * 0.22, 5);
}

void terraces(NetworkLines& out, double size, SplitMix64& rng) {
  const double spacing = 35.0;
  const int rows = int(size / spacing);
  std::vector<std::vector<Vec2>> walls;
  for (int r = 0; r < rows; ++r) {
    std::vector<Vec2> wall;
    for (int i = 0; i <= 40; ++i) {
      const double x = size * i / 40.0;
      wall.push_back({x, r * spacing + 8.0 * std::sin(x / 90.0 + 0.3 * r)});
    }
    walls.push_back(wall);
    add(out, wall);
  }
  for (int r = 0; r + 1 < rows; ++r)  // ramps between consecutive walls
    for (int i = 2; i < 40; i += 5 + int(rng.below(5))) {
      const Vec2 a = walls[std::size_t(r)][std::size_t(i)];
      const Vec2 b = walls[std::size_t(r) + 1][std::size_t(i) + 1];
      add(out, {a, b});
    }
}

void radial(NetworkLines& out, double size, SplitMix64& rng) {
  const Vec2 c{size / 2, size / 2};
  const int rings = 5;
  const double step = size / 2 / (rings + 0.5);
  for (int r = 1; r <= rings; ++r) {
    std::vector<Vec2> ring;
    for (int i = 0; i <= 96; ++i) {
      const double a = 2 * kPi * i / 96;
      ring.push_back(c + Vec2{std::cos(a), std::sin(a)} * (r * step));
    }
    ring.back() = ring.front();
    add(out, ring);
  }
  for (int s = 0; s < 12; ++s) {
    const double a = 2 * kPi * s / 12 + rng.uniform(-0.05, 0.05);
    const double from = (s % 2 == 0) ? 0.0 : step;  // every other spoke starts at the first ring
    if (from == 0.0)
      add(out, {c, c + Vec2{std::cos(a), std::sin(a)} * (rings * step)});
    else
      add(out, {c + Vec2{std::cos(a), std::sin(a)} * from,
                c + Vec2{std::cos(a), std::sin(a)} * (rings * step)});
  }
}

void crocodile(NetworkLines& out, double size, SplitMix64& rng) {
  // A jittered hexagonal lattice: cells of ~30 m meeting three by three.
  const double a = 18.0;
  const double w = std::sqrt(3.0) * a;
  const int nx = int(size / w), ny = int(size / (1.5 * a));
  std::map<std::pair<long, long>, Vec2> vertex;
  const auto v = [&](double x, double y) {
    const auto key = std::pair{std::lround(x * 10), std::lround(y * 10)};
    auto it = vertex.find(key);
    if (it == vertex.end())
      it = vertex.emplace(key, Vec2{x + rng.uniform(-4, 4), y + rng.uniform(-4, 4)}).first;
    return it->second;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c{i * w + (j % 2) * w / 2, j * 1.5 * a};
      std::vector<Vec2> ring;
      for (int k = 0; k <= 6; ++k) {
        const double ang = kPi / 6 + kPi / 3 * (k % 6);
        ring.push_back(v(c.x + a * std::cos(ang), c.y + a * std::sin(ang)));
      }
      add(out, ring);
    }
}

}  // namespace

NetworkLines example_network(const std::string& kind, double size_m, std::uint64_t seed) {
  SplitMix64 rng(seed);
  NetworkLines out;
  if (kind == "grid")
    grid(out, size_m, rng);
  else if (kind == "bocage")
    split_cells(out, size_m, rng, 9000.0, 0.0);
  else if (kind == "drainage")
    drainage(out, size_m, rng);
  else if (kind == "terraces")
    terraces(out, size_m, rng);
  else if (kind == "radial")
    radial(out, size_m, rng);
  else if (kind == "crocodile")
    crocodile(out, size_m, rng);
  else
    fail("example network '{}': unknown kind", kind);
  return out;
}

}  // namespace tw
