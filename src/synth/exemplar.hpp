#pragma once
// Exemplars (Zhou et al. 2013, "Input exemplars"): an image whose alpha outlines the geometry
// of the pattern, read through OpenImageIO (PNG, TIFF, EXR, ...). Extra channels (height,
// material weights) ride along unchanged to the rendered output.
#include <cstddef>
#include <string>
#include <vector>

#include "synth/detail/stages.hpp"

namespace tw {

struct ExemplarOptions {
  // Optional single-channel image of the same size, appended as the channel "height".
  std::string height_path;
  // Refuse exemplars whose float texels (all channels) would exceed this many bytes.
  std::size_t memory_budget_bytes = std::size_t(256) << 20;
  // Continuous-alpha costs (the paper's suggestion for semi-transparent exemplars).
  bool continuous_alpha = false;
};

struct Exemplar {
  int width = 0;
  int height = 0;
  std::vector<std::string> channel_names;  // e.g. R, G, B, A, height
  std::vector<float> texels;               // interleaved, row-major, y down; colours 0..1
  detail::CostTexels cost;                 // RGBA8, premultiplied, for the DP costs
  std::string path;                        // where it came from (for messages)

  int channel_count() const { return int(channel_names.size()); }
  int channel_index(const std::string& name) const;  // -1 when absent
  float at(int x, int y, int c) const {
    return texels[(std::size_t(y) * width + x) * channel_names.size() + c];
  }
};

// Throws tw::Error naming the file: unreadable, no alpha channel, fully transparent, fully
// opaque, over the memory budget, height image of another size.
Exemplar load_exemplar(const std::string& path, const ExemplarOptions& options = {});

// An exemplar from texels in memory (generated patterns, tests). Channels must include "A";
// "R", "G", "B" (or "Y") give the colour of the cost. `label` names it in messages.
Exemplar make_exemplar(int width, int height, std::vector<std::string> channel_names,
                       std::vector<float> texels, const std::string& label,
                       bool continuous_alpha = false);

}  // namespace tw
