#include "layers/compare.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "layers/detail/band_reader.hpp"

namespace tw {

namespace {

constexpr int kRowsPerRead = 64;

void compare_value(float a, float b, int col, int row, BandDifference& d) {
  const bool a_nan = std::isnan(a), b_nan = std::isnan(b);
  if (a_nan && b_nan) return;
  if (a_nan != b_nan) {
    ++d.differing;
    ++d.nodata_mismatch;
    return;
  }
  if (a == b) return;
  ++d.differing;
  const double diff = std::abs(double(a) - double(b));
  if (diff > d.max_abs) {  // the first pixel in row order wins a tie
    d.max_abs = diff;
    d.col = col;
    d.row = row;
    d.a = a;
    d.b = b;
  }
}

}  // namespace

bool RasterDifference::identical() const {
  if (!size_mismatch.empty() || !only_in_a.empty() || !only_in_b.empty()) return false;
  return std::all_of(bands.begin(), bands.end(),
                     [](const BandDifference& d) { return d.differing == 0; });
}

RasterDifference compare_rasters(const std::filesystem::path& a, const std::filesystem::path& b) {
  const auto reader_a = detail::open_band_reader(a);
  const auto reader_b = detail::open_band_reader(b);
  RasterDifference result;
  // Bands matched by name: index in a, index in b.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < reader_a->bands.size(); ++i) {
    const auto found =
        std::find(reader_b->bands.begin(), reader_b->bands.end(), reader_a->bands[i]);
    if (found == reader_b->bands.end()) {
      result.only_in_a.push_back(reader_a->bands[i]);
    } else {
      pairs.emplace_back(i, std::size_t(found - reader_b->bands.begin()));
      result.bands.push_back({reader_a->bands[i]});
    }
  }
  for (const std::string& name : reader_b->bands)
    if (std::find(reader_a->bands.begin(), reader_a->bands.end(), name) == reader_a->bands.end())
      result.only_in_b.push_back(name);
  if (reader_a->width != reader_b->width || reader_a->height != reader_b->height) {
    result.size_mismatch = fmt::format("{} x {} vs {} x {}", reader_a->width, reader_a->height,
                                       reader_b->width, reader_b->height);
    return result;
  }
  const int width = reader_a->width;
  std::vector<float> rows_a, rows_b;
  for (int row = 0; row < reader_a->height; row += kRowsPerRead) {
    const int rows = std::min(kRowsPerRead, reader_a->height - row);
    reader_a->read_rows(row, rows, rows_a);
    reader_b->read_rows(row, rows, rows_b);
    const std::size_t pixels = std::size_t(rows) * width;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const float* pa = rows_a.data() + pairs[k].first * pixels;
      const float* pb = rows_b.data() + pairs[k].second * pixels;
      for (std::size_t p = 0; p < pixels; ++p)
        compare_value(pa[p], pb[p], int(p % width), row + int(p / width), result.bands[k]);
    }
  }
  return result;
}

}  // namespace tw
