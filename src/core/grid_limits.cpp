#include "core/grid_limits.hpp"

#include <cmath>
#include <limits>

#include <unistd.h>

#include "core/error.hpp"

namespace tw {

void require_grid_size(double columns, double rows, const std::string& what) {
  if (!(columns >= 1.0 && rows >= 1.0)) {
    fail("{} gives a grid of {:.6g} x {:.6g} cells; it needs at least one", what, columns, rows);
  }
  const double cells = columns * rows;
  if (cells > double(kMaxGridCells) || columns > std::numeric_limits<int>::max() ||
      rows > std::numeric_limits<int>::max()) {
    const double gib = cells * sizeof(float) / double(std::int64_t(1) << 30);
    fail(
        "{} gives a {:.0f} x {:.0f} grid ({:.3g} GiB per float band); at most {} cells are "
        "allowed",
        what, columns, rows, gib, kMaxGridCells);
  }
}

double memory_budget_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 8.0 * double(std::int64_t(1) << 30);
  return 0.75 * double(pages) * double(page);
}

}  // namespace tw
