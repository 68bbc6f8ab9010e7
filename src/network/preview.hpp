#pragma once
// A PNG picture of networks (docs/networks.md): the region tinted, forbidden cells pale red,
// then each layer's lines in
// its colour; several panels side by side (exemplar beside output). Written through GDAL's PNG
// driver to the path given (stage it: core/atomic_output.hpp).
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "network/growth.hpp"
#include "network/network.hpp"
#include "raster/polygon.hpp"

namespace tw {

struct PreviewLayer {
  const Network* network = nullptr;
  std::array<std::uint8_t, 3> colour{40, 80, 40};
  double width_px = 2.0;
};

struct PreviewPanel {
  std::vector<Polygon> region;  // tinted; its extent (or the layers') frames the panel
  std::vector<PreviewLayer> layers;
  const ForbiddenMask* forbidden = nullptr;  // drawn pale red under the lines
};

// `size_px`: the longest side of each panel.
void write_network_png(const std::filesystem::path& path, const std::vector<PreviewPanel>& panels,
                       int size_px = 800);

}  // namespace tw
