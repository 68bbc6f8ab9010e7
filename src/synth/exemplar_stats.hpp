#pragma once
// What an exemplar implies for its synthesis (`terraweave exemplar inspect`): the rows that
// hold its pattern (the ribbon width that holds it), its period along x, a piece length δ, its
// coverage, whether it tiles. Synthesis defaults come from here when the user gives none.
#include <string>
#include <vector>

#include "synth/exemplar.hpp"

namespace tw {

struct ExemplarStats {
  int width = 0, height = 0;
  // The band: rows band_top..band_bottom (inclusive) hold all opaque texels (alpha >= 0.5) but
  // the 1 % at either end (stray texels outside the pattern are not the pattern).
  int band_top = 0, band_bottom = 0;
  int band_rows() const { return band_bottom - band_top + 1; }
  double band_centre = 0.0;             // (band_top + band_bottom + 1) / 2, in texel rows
  double opaque_fraction = 0.0;         // of the whole image
  double natural_coverage = 0.0;        // opaque fraction of the band rows (all columns)
  std::vector<double> column_coverage;  // per column, opaque fraction of the band rows
  double min_column_coverage = 0.0, max_column_coverage = 0.0;
  // Period along x: the lag in [2, W/2] of the autocorrelation peak of the columns' opacity
  // and luminance profile; 0 when no lag correlates at 0.3 or more (aperiodic).
  int period = 0;
  double period_correlation = 0.0;
  int suggested_delta = 0;  // piece length in texels: the period (or a divisor within a band)
  // Coverage floor (SynthParams::min_coverage) suggested for a window of band_rows rows.
  double suggested_min_coverage = 0.0;
  // Tiles along x: the seam from the last column to the first costs no more than twice the
  // median cost between neighbouring columns (colour units per band texel).
  bool cyclic = false;
  double wrap_seam_cost = 0.0, median_column_step = 0.0;
};

// Fraction of the natural coverage that the suggested coverage floor asks of each piece.
inline constexpr double kCoverageFloorOfNatural = 0.1;

ExemplarStats exemplar_stats(const Exemplar& exemplar);

// The synthesis defaults the exemplar implies at `scale` texels per metre (used where the user
// gives no width or delta), in metres: the band's rows plus a margin of an eighth of them and a
// row on either side (a piece's top and bottom edges must cross transparent texels, and on a
// curve they slant across rows), and the suggested δ.
inline double suggested_width(const ExemplarStats& s, double scale) {
  return (s.band_rows() + 2 * (s.band_rows() / 8 + 1)) / scale;
}
inline double suggested_delta(const ExemplarStats& s, double scale) {
  return s.suggested_delta / scale;
}

// Opaque fraction of a window of `rows` rows centred on the band, over all columns (the natural
// coverage of a ribbon C = rows texels wide).
double window_coverage(const Exemplar& exemplar, const ExemplarStats& stats, int rows);

// The exemplar with its statistics drawn over it (band rows, centre line, period ticks and the
// per-column coverage as a bar strip below), as 8-bit RGB of width W and height H + 24.
struct StatsPreview {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};
StatsPreview stats_preview(const Exemplar& exemplar, const ExemplarStats& stats);

}  // namespace tw
