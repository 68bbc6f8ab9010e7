#pragma once
// The largest raster terraweave allocates. Sizes are checked in double before any int
// conversion or allocation, so an absurd resolution, pixel size or canvas gives one clear
// error instead of an overflowed size, a bad_alloc or hours of work (docs/robustness.md).
#include <cstdint>
#include <string>

namespace tw {

// 2^30 cells: 4 GiB per float band (e.g. 32768 x 32768).
inline constexpr std::int64_t kMaxGridCells = std::int64_t(1) << 30;

// Fails (tw::Error) unless columns x rows is a grid of at least one cell and at most
// kMaxGridCells, each side fitting an int: "<what> gives a W x H grid (N GiB per float band);
// at most 1073741824 cells are allowed". `what` names the cause ("dem.tif: resolution 0.1 m").
void require_grid_size(double columns, double rows, const std::string& what);

// The bytes one polygon's synthesis (an area's canvas and shapes) may claim before it is refused
// with its estimate: three quarters of the machine's physical memory (8 GiB where unknown).
double memory_budget_bytes();

}  // namespace tw
