#pragma once
// A vector exemplar for structured shape-patterns (Olivier, Memari & Cani, "Structured
// Shape-Patterns from a Sketch", Section 3.2): strokes drawn once in a square input space.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

struct Stroke {
  std::vector<Vec2> points;  // input-space coordinates, [0, 1] x [0, 1], y up
  // Unbounded strokes stand for fibres that go on beyond the input space (the paper's second
  // pen); bounded ones are parts of shapes that repeat.
  bool unbounded = false;
  std::string material;     // splat material (or instance type) it is drawn with
  double thickness = 0.01;  // input-space units
  std::int64_t fid = -1;    // feature id in the sketch file
};

struct Sketch {
  std::vector<Stroke> strokes;
  std::string source;  // the file, for messages
};

// Reads a sketch from any OGR source (GeoJSON in samples/sketches): one LineString (or
// MultiLineString, one stroke per part) per stroke with optional attributes `type`
// ("bounded" | "unbounded", default bounded), `material` (default "shape") and `thickness`
// (input-space units, default 0.01). Coordinates must lie in [0, 1]^2 (1e-6 tolerance). Throws
// tw::Error naming the file and FID of the first stroke it cannot use.
Sketch load_sketch(const std::filesystem::path& path);

// Checks the invariants load_sketch guarantees (for sketches built in code): at least one stroke,
// every stroke with two or more distinct finite points inside the input space, thickness > 0.
void check_sketch(const Sketch& sketch);

}  // namespace tw
