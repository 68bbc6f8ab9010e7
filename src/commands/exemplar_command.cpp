#include "commands/exemplar_command.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "geo/input_guard.hpp"
#include "image/image_io.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"

namespace tw {
namespace {

void write_preview(const std::filesystem::path& path, const StatsPreview& preview) {
  OutputTransaction transaction;
  const std::string staged = transaction.stage(path).string();
  write_rgb8_image(staged, preview.width, preview.height, preview.rgb.data(), path.string());
  transaction.commit();
}

}  // namespace

std::string run_exemplar_inspect(const ExemplarInspectCommand& c) {
  set_network_access(c.allow_network);
  check_input_path(c.exemplar.string(), "exemplar", c.allow_network);
  ExemplarOptions options;
  options.continuous_alpha = c.continuous_alpha;
  const Exemplar exemplar = load_exemplar(c.exemplar.string(), options);
  const ExemplarStats s = exemplar_stats(exemplar);
  if (!c.preview.empty()) write_preview(c.preview, stats_preview(exemplar, s));
  if (c.json) {
    nlohmann::json j = {{"exemplar", c.exemplar.string()},
                        {"width", s.width},
                        {"height", s.height},
                        {"band_rows", {s.band_top, s.band_bottom}},
                        {"band_height", s.band_rows()},
                        {"band_centre", s.band_centre},
        {"suggested_width", suggested_width(s, 1.0)},
                        {"opaque_fraction", s.opaque_fraction},
                        {"natural_coverage", s.natural_coverage},
                        {"column_coverage",
                         {{"min", s.min_column_coverage},
                          {"max", s.max_column_coverage},
                          {"values", s.column_coverage}}},
                        {"period", s.period},
                        {"period_correlation", s.period_correlation},
                        {"suggested_delta", s.suggested_delta},
                        {"suggested_min_coverage", s.suggested_min_coverage},
                        {"cyclic", s.cyclic},
                        {"wrap_seam_cost", s.wrap_seam_cost},
                        {"median_column_step", s.median_column_step}};
    return j.dump(2) + "\n";
  }
  std::string out = fmt::format("{}: {} x {} texels\n", c.exemplar.string(), s.width, s.height);
  out += fmt::format(
      "  opaque rows   {}..{} ({} rows, centre {:.1f}): a ribbon of {} texels holds the pattern "
      "(suggested --width {} / scale, with clear margins)\n",
      s.band_top, s.band_bottom, s.band_rows(), s.band_centre, s.band_rows(),
      suggested_width(s, 1.0));
  out += s.period > 0 ? fmt::format("  period along x {} texels (autocorrelation {:.2f})\n",
                                    s.period, s.period_correlation)
                      : std::string("  period along x none (aperiodic)\n");
  out += fmt::format("  suggested delta {} texels (--delta {} / scale)\n", s.suggested_delta,
                     s.suggested_delta);
  out += fmt::format(
      "  coverage      {:.3f} of the band rows (natural), columns {:.3f}..{:.3f}, {:.3f} of the "
      "image\n",
      s.natural_coverage, s.min_column_coverage, s.max_column_coverage, s.opaque_fraction);
  out += fmt::format("  coverage floor {:.3f} (min_coverage default)\n", s.suggested_min_coverage);
  out += fmt::format("  cyclic        {} (wrap seam {:.1f} vs median column step {:.1f})\n",
                     s.cyclic ? "yes" : "no", s.wrap_seam_cost, s.median_column_step);
  return out;
}

}  // namespace tw
