#include "raster/detail/window_raster.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw::detail {

void check_window(const Window& window, const char* who) {
  if (window.width < 0 || window.height < 0)
    fail("{}: window {}x{} has a negative size", who, window.width, window.height);
}

void prepare_window_raster(Raster<std::uint8_t>& out, const Window& window, const char* who) {
  check_window(window, who);
  if (out.pixels.empty() && out.width == 0 && out.height == 0) {
    out = Raster<std::uint8_t>(window.width, window.height, 0);
    return;
  }
  if (out.width != window.width || out.height != window.height ||
      out.pixels.size() != std::size_t(window.width) * window.height)
    fail("{}: output raster is {}x{} but the window is {}x{}", who, out.width, out.height,
         window.width, window.height);
}

}  // namespace tw::detail
