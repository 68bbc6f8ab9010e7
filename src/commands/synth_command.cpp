#include "commands/synth_command.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/features.hpp"
#include "geo/input_guard.hpp"
#include "image/image_io.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/placements_io.hpp"
#include "synth/render.hpp"
#include "synth/shapes.hpp"

namespace tw {

namespace {

bool is_shape(const std::string& name) {
  for (const char* s : {"line", "arc", "s-curve", "circle", "heart", "hairpin"}) {
    if (name == s) return true;
  }
  return false;
}

// The first line of "path" or "path:layer" as a curve (a closed ring stays closed), with the
// pipeline's checks on its coordinates.
Curve read_first_line(const std::string& source) {
  VectorSource vector;
  vector.path = source;
  if (const auto colon = source.rfind(':'); colon != std::string::npos && colon > 1) {
    vector.path = source.substr(0, colon);
    vector.layer = source.substr(colon + 1);
  }
  LineFeature line = read_first_line_feature(vector);
  return without_duplicates(Curve{std::move(line.points), line.closed});
}

// A canvas of one pixel per exemplar texel around the ribbon, with a margin of a width.
GridSpec canvas_around(const Curve& curve, double width, double scale) {
  Vec2 lo = curve.points.front(), hi = lo;
  for (const Vec2 p : curve.points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  GridSpec grid;
  grid.pixel_width = grid.pixel_height = 1.0 / scale;
  grid.origin_x = lo.x - width;
  grid.origin_y = hi.y + width;
  // Sized in double: a huge width or scale must not overflow int before the check.
  const double columns = std::ceil((hi.x - lo.x + 2 * width) * scale);
  const double rows = std::ceil((hi.y - lo.y + 2 * width) * scale);
  if (!(columns * rows <= 64.0 * 1024 * 1024)) {
    fail(
        "synth: a canvas of {:.6g} x {:.6g} pixels is too large (at most 64 Mi); lower --scale, "
        "--width or --length",
        columns, rows);
  }
  grid.width = int(columns);
  grid.height = int(rows);
  return grid;
}

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgb) {
  write_rgb8_image(path.string(), width, height, rgb.data(), path.string());
}

}  // namespace

Synthesis run_synth_command(const SynthCommand& c) {
  if (!(c.width >= 0)) fail("synth: --width must be > 0 metres, got {}", c.width);
  if (!(c.delta >= 0)) fail("synth: --delta must be > 0 metres, got {}", c.delta);
  if (!(c.scale > 0)) fail("synth: --scale must be > 0 texels per metre, got {}", c.scale);
  if (!(c.length > 0)) fail("synth: --length must be > 0 metres, got {}", c.length);
  if (!(c.feather >= 0)) fail("synth: --feather must be >= 0 metres, got {}", c.feather);
  set_network_access(c.allow_network);
  check_input_path(c.exemplar.string(), "--exemplar", c.allow_network);
  if (!is_shape(c.curve)) check_input_path(c.curve, "--curve", c.allow_network);
  ExemplarOptions options;
  options.continuous_alpha = c.continuous_alpha;
  const Exemplar exemplar = load_exemplar(c.exemplar.string(), options);
  const ExemplarStats stats = exemplar_stats(exemplar);
  const double width = c.width > 0 ? c.width : suggested_width(stats, c.scale);
  const double delta = c.delta > 0 ? c.delta : suggested_delta(stats, c.scale);
  if (c.width <= 0 || c.delta <= 0)
    logger().info("synth: from the exemplar: width {:.3g} m ({} rows), delta {:.3g} m", width,
                  stats.band_rows(), delta);
  const Curve curve = is_shape(c.curve) ? make_shape(c.curve, c.length) : read_first_line(c.curve);
  const Ribbon ribbon = make_ribbon(curve, {width, delta, 0.0});
  const GridSpec canvas = canvas_around(curve, width, c.scale);
  SynthParams params;
  params.scale = c.scale;
  params.seed = c.seed;
  params.stitch = c.stitch;
  params.min_coverage = c.min_coverage;
  params.objective = c.objective;
  params.coverage_weight = c.coverage_weight;
  params.backend = parse_backend_kind(c.backend);
  params.feature_label = c.curve;
  const Synthesis synthesis = synthesize(exemplar, ribbon, canvas, nullptr, params);

  const Window whole = Window::whole(canvas);
  const RenderedPattern pattern =
      render_pattern(exemplar, ribbon, synthesis, canvas, whole, c.stitch, c.feather);
  const Raster<float> cage = render_cage(ribbon, canvas, whole);
  const int r = exemplar.channel_index("R"), g = exemplar.channel_index("G"),
            b = exemplar.channel_index("B");
  std::vector<std::uint8_t> rgb(std::size_t(canvas.width) * canvas.height * 3);
  for (std::size_t i = 0; i < cage.pixels.size(); ++i) {
    const float alpha = pattern.coverage.pixels[i];
    for (int k = 0; k < 3; ++k) {
      const int channel = k == 0 ? r : k == 1 ? g : b;
      // Channels are alpha-weighted means: colour over white is channel * alpha + (1 - alpha).
      const float colour = channel >= 0 ? pattern.channels[channel].pixels[i] : 0.0f;
      float v = colour * alpha + (1.0f - alpha);
      if (cage.pixels[i] > 0.5f) v = k == 0 ? 0.85f : 0.1f;  // the cage in red
      rgb[i * 3 + k] = std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
  }
  OutputTransaction transaction;
  write_png(transaction.stage(c.output), canvas.width, canvas.height, rgb);
  if (!c.placements.empty()) {
    save_placements(synthesis, c.exemplar.string(), transaction.stage(c.placements).string());
  }
  transaction.commit();
  logger().info("synth: {} pieces, Omega {} ({:.2f} per seam, {:.2f} stitched), backend {}",
                ribbon.pieces.size(), synthesis.total_cost, synthesis.mean_seam_cost,
                synthesis.mean_seam_cost_stitched, synthesis.backend);
  return synthesis;
}

}  // namespace tw
