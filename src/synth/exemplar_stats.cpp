#include "synth/exemplar_stats.hpp"

#include <algorithm>
#include <cmath>

#include "synth/detail/cost.hpp"

namespace tw {
namespace {

using detail::is_opaque;

std::uint32_t texel(const Exemplar& e, int x, int y) {
  return e.cost.rgba[std::size_t(y) * e.width + x];
}

double luminance(std::uint32_t t) {
  return (0.299 * detail::channel_of(t, 0) + 0.587 * detail::channel_of(t, 1) +
          0.114 * detail::channel_of(t, 2)) /
         255.0;
}

// Rows holding all opaque texels but the `trim` fraction at either end.
void find_band(const Exemplar& e, ExemplarStats& s) {
  std::vector<std::int64_t> rows(std::size_t(e.height), 0);
  std::int64_t total = 0;
  for (int y = 0; y < e.height; ++y)
    for (int x = 0; x < e.width; ++x) rows[std::size_t(y)] += is_opaque(texel(e, x, y));
  for (auto r : rows) total += r;
  const double trim = 0.01 * double(total);
  std::int64_t seen = 0;
  s.band_top = 0;
  while (s.band_top < e.height - 1 && double(seen + rows[std::size_t(s.band_top)]) <= trim)
    seen += rows[std::size_t(s.band_top++)];
  seen = 0;
  s.band_bottom = e.height - 1;
  while (s.band_bottom > s.band_top && double(seen + rows[std::size_t(s.band_bottom)]) <= trim)
    seen += rows[std::size_t(s.band_bottom--)];
  s.band_centre = (s.band_top + s.band_bottom + 1) / 2.0;
  s.opaque_fraction = double(total) / (double(e.width) * e.height);
}

// Autocorrelation of the columns' opacity and luminance in the band; the first lag whose
// peak reaches 85 % of the best one.
void find_period(const std::vector<double>& opacity, const std::vector<double>& light,
                 ExemplarStats& s) {
  const int W = int(opacity.size());
  double mo = 0, ml = 0;
  for (int x = 0; x < W; ++x) mo += opacity[std::size_t(x)], ml += light[std::size_t(x)];
  mo /= W, ml /= W;
  double variance = 0;
  for (int x = 0; x < W; ++x)
    variance += std::pow(opacity[std::size_t(x)] - mo, 2) + std::pow(light[std::size_t(x)] - ml, 2);
  variance /= W;
  if (!(variance > 1e-12) || W < 8) return;
  std::vector<double> r(std::size_t(W / 2 + 2), 0.0);
  for (int p = 1; p <= W / 2 + 1 && p < W; ++p) {
    double sum = 0;
    for (int x = 0; x + p < W; ++x)
      sum += (opacity[std::size_t(x)] - mo) * (opacity[std::size_t(x + p)] - mo) +
             (light[std::size_t(x)] - ml) * (light[std::size_t(x + p)] - ml);
    r[std::size_t(p)] = sum / (W - p) / variance;
  }
  double best = 0;
  for (int p = 2; p <= W / 2; ++p)
    if (r[std::size_t(p)] >= r[std::size_t(p - 1)] && r[std::size_t(p)] >= r[std::size_t(p + 1)])
      best = std::max(best, r[std::size_t(p)]);
  if (best < 0.3) return;
  for (int p = 2; p <= W / 2; ++p) {
    if (r[std::size_t(p)] >= r[std::size_t(p - 1)] && r[std::size_t(p)] >= r[std::size_t(p + 1)] &&
        r[std::size_t(p)] >= 0.85 * best) {
      s.period = p;
      s.period_correlation = r[std::size_t(p)];
      return;
    }
  }
}

double column_step(const Exemplar& e, const ExemplarStats& s, int a, int b) {
  std::int64_t sum = 0;
  for (int y = s.band_top; y <= s.band_bottom; ++y)
    sum += detail::xi(texel(e, a, y), texel(e, b, y), e.cost.binary_alpha);
  return double(sum) / s.band_rows() / detail::kColourScale;
}

}  // namespace

ExemplarStats exemplar_stats(const Exemplar& e) {
  ExemplarStats s;
  s.width = e.width, s.height = e.height;
  find_band(e, s);
  std::vector<double> light(std::size_t(e.width), 0.0);
  s.column_coverage.assign(std::size_t(e.width), 0.0);
  for (int x = 0; x < e.width; ++x) {
    for (int y = s.band_top; y <= s.band_bottom; ++y) {
      s.column_coverage[std::size_t(x)] += is_opaque(texel(e, x, y));
      light[std::size_t(x)] += luminance(texel(e, x, y));
    }
    s.column_coverage[std::size_t(x)] /= s.band_rows();
    light[std::size_t(x)] /= s.band_rows();
    s.natural_coverage += s.column_coverage[std::size_t(x)] / e.width;
  }
  const auto [lo, hi] = std::minmax_element(s.column_coverage.begin(), s.column_coverage.end());
  s.min_column_coverage = *lo, s.max_column_coverage = *hi;
  find_period(s.column_coverage, light, s);

  // δ: one period, or the largest divisor of it within the band's height (short pieces bend
  // with the curve); aperiodic: half the band. At least 4 texels, at most a third of W.
  int delta = std::max(4, s.band_rows() / 2);
  if (s.period > 0) {
    delta = s.period;
    for (int k = 2; delta > s.band_rows() && s.period / k >= 4; ++k)
      delta = int(std::lround(double(s.period) / k));
  }
  s.suggested_delta = std::clamp(delta, 1, std::max(1, e.width / 3));
  s.suggested_min_coverage = kCoverageFloorOfNatural * s.natural_coverage;

  std::vector<double> steps;
  for (int x = 0; x + 1 < e.width; ++x) steps.push_back(column_step(e, s, x, x + 1));
  if (!steps.empty()) {
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    s.median_column_step = steps[steps.size() / 2];
  }
  s.wrap_seam_cost = column_step(e, s, e.width - 1, 0);
  s.cyclic = s.wrap_seam_cost <= 2.0 * s.median_column_step + 1.0;
  return s;
}

double window_coverage(const Exemplar& e, const ExemplarStats& s, int rows) {
  if (rows <= 0) return 0.0;
  const int top = int(std::floor(s.band_centre - rows / 2.0 + 0.5));
  std::int64_t opaque = 0;
  for (int y = std::max(0, top); y < std::min(e.height, top + rows); ++y)
    for (int x = 0; x < e.width; ++x) opaque += is_opaque(texel(e, x, y));
  return double(opaque) / (double(rows) * e.width);
}

StatsPreview stats_preview(const Exemplar& e, const ExemplarStats& s) {
  constexpr int kStrip = 24;
  StatsPreview p{e.width, e.height + kStrip, {}};
  p.rgb.assign(std::size_t(p.width) * p.height * 3, 255);
  auto put = [&](int x, int y, int r, int g, int b) {
    if (x < 0 || y < 0 || x >= p.width || y >= p.height) return;
    unsigned char* q = p.rgb.data() + (std::size_t(y) * p.width + x) * 3;
    q[0] = (unsigned char)r, q[1] = (unsigned char)g, q[2] = (unsigned char)b;
  };
  for (int y = 0; y < e.height; ++y) {
    for (int x = 0; x < e.width; ++x) {
      const std::uint32_t t = texel(e, x, y);  // premultiplied: over white add 255 - alpha
      const int a = int(detail::alpha_of(t));
      const int checker = ((x / 4 + y / 4) % 2) ? 235 : 255;
      const int bg = checker * (255 - a) / 255;
      put(x, y, int(detail::channel_of(t, 0)) + bg, int(detail::channel_of(t, 1)) + bg,
          int(detail::channel_of(t, 2)) + bg);
    }
  }
  for (int x = 0; x < e.width; ++x) {
    put(x, s.band_top, 30, 60, 230);  // band rows in blue
    put(x, s.band_bottom, 30, 60, 230);
    if (x % 4 < 2) put(x, int(s.band_centre), 20, 170, 40);  // centre, dashed green
    const int bar = int(std::lround(s.column_coverage[std::size_t(x)] * (kStrip - 2)));
    for (int k = 0; k < bar; ++k) put(x, p.height - 1 - k, 90, 90, 90);
  }
  const int natural = p.height - 1 - int(std::lround(s.natural_coverage * (kStrip - 2)));
  for (int x = 0; x < e.width; ++x) put(x, natural, 20, 170, 40);
  if (s.period > 0)  // period ticks in red along the top
    for (int x = 0; x < e.width; x += s.period)
      for (int y = 0; y < 6; ++y) put(x, y, 220, 30, 30);
  return p;
}

}  // namespace tw
