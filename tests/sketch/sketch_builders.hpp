#pragma once
// Small sketches with known structure, built in code.
#include <cmath>
#include <numbers>

#include "sketch/sketch.hpp"

namespace tw::test {

inline Stroke line_stroke(Vec2 a, Vec2 b, bool unbounded, double thickness = 0.01,
                          const char* material = "line") {
  Stroke s;
  for (int k = 0; k <= 8; ++k) s.points.push_back(lerp(a, b, k / 8.0));
  s.unbounded = unbounded;
  s.thickness = thickness;
  s.material = material;
  return s;
}

// A small closed ring of radius r: a bounded, isotropic shape (a tree, a boulder).
inline Stroke dot_stroke(Vec2 c, double r, const char* material = "tree") {
  Stroke s;
  for (int k = 0; k <= 12; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 12.0;
    s.points.push_back(c + Vec2{std::cos(a), std::sin(a)} * r);
  }
  s.thickness = 0.004;
  s.material = material;
  return s;
}

// Four horizontal unbounded lines (y = 0.2 ... 0.8) and three at 60 degrees.
inline Sketch two_families() {
  Sketch sketch;
  sketch.source = "two_families";
  for (double y : {0.2, 0.4, 0.6, 0.8}) {
    sketch.strokes.push_back(line_stroke({0.0, y}, {1.0, y}, true));
  }
  const Vec2 d{std::cos(std::numbers::pi / 3), std::sin(std::numbers::pi / 3)};
  for (double x : {0.3, 0.5, 0.7}) {
    const Vec2 c{x, 0.5};
    sketch.strokes.push_back(line_stroke(c - d * 0.25, c + d * 0.25, true));
  }
  return sketch;
}

// Rows of dots every 0.1 along x, rows every 0.2 along y, odd rows shifted by 0.05.
inline Sketch staggered_dots() {
  Sketch sketch;
  sketch.source = "staggered_dots";
  for (int row = 0; row < 5; ++row) {
    const bool odd = row % 2 == 1;
    for (int k = 0; k < (odd ? 8 : 9); ++k) {
      sketch.strokes.push_back(dot_stroke({(odd ? 0.15 : 0.1) + 0.1 * k, 0.1 + 0.2 * row}, 0.015));
    }
  }
  return sketch;
}

// One sinusoidal unbounded stroke across the input space: appears once, never repeated (H2).
inline Sketch single_wave() {
  Sketch sketch;
  sketch.source = "single_wave";
  Stroke s;
  for (int k = 0; k <= 64; ++k) {
    const double x = k / 64.0;
    s.points.push_back({x, 0.5 + 0.1 * std::sin(2.0 * std::numbers::pi * 1.5 * x)});
  }
  s.unbounded = true;
  s.thickness = 0.01;
  s.material = "hedge";
  sketch.strokes.push_back(s);
  return sketch;
}

}  // namespace tw::test
