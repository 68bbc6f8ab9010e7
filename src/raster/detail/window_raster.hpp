#pragma once
// Small helpers for window-sized outputs.
#include <cstdint>
#include <vector>

#include "core/grid.hpp"

namespace tw::detail {

// Allocates `out` for the window when empty; throws tw::Error when it has another size.
void prepare_window_raster(Raster<std::uint8_t>& out, const Window& window, const char* who);
// Throws tw::Error when the window is negative-sized.
void check_window(const Window& window, const char* who);

}  // namespace tw::detail
