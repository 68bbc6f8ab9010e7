#pragma once
// `terraweave synth`: one ribbon along a built-in shape or the first line of an OGR layer,
// synthesized from an exemplar and drawn (pattern over white, ribbon cage on top) into a PNG.
#include <cstdint>
#include <filesystem>
#include <string>

#include "synth/synthesize.hpp"

namespace tw {

struct SynthCommand {
  std::filesystem::path exemplar;
  // A shape of synth/shapes.hpp (line, arc, s-curve, circle, heart, hairpin) or an OGR source
  // "path" or "path:layer" in a projected CRS (metres); its first feature is used.
  std::string curve;
  double length = 200.0;  // metres, the size of a built-in shape
  double width = 0.0;     // b, metres; 0: the exemplar's band (exemplar_stats)
  double delta = 0.0;     // piece length, metres; 0: the exemplar's suggested δ
  double scale = 0.0;     // exemplar texels per metre; the canvas has one pixel per texel
  std::string backend = "auto";
  std::uint64_t seed = 0;
  bool stitch = true;
  double min_coverage = -1.0;        // SynthParams::min_coverage (< 0: from the exemplar)
  Objective objective = Objective::pattern;
  double coverage_weight = 2.0;      // SynthParams::coverage_weight
  bool continuous_alpha = false;     // ExemplarOptions::continuous_alpha
  double feather = 0.0;              // render_pattern's seam feathering, metres
  std::filesystem::path output;      // .png
  std::filesystem::path placements;  // optional JSON of the placements (synth/placements_io.hpp)
  bool allow_network = false;        // --exemplar and --curve may be URLs (/vsicurl/...)
};

// Throws tw::Error naming the exemplar, the curve source or the value at fault. The PNG is
// written atomically. Returns the synthesis (costs, valid positions, timings).
Synthesis run_synth_command(const SynthCommand& command);

}  // namespace tw
