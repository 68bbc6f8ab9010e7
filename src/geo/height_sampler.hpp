#pragma once
// Heights of a HeightfieldSource read through a small cache of square blocks (least recently
// used out past a byte cap): stages that follow features (terrain profiles, conformance) touch
// the cells along them, never the world. Values are those of the whole raster, bit for bit
// (sample_height_bilinear over the whole read), whatever the block size and cap.
#include <cstdint>
#include <list>
#include <unordered_map>
#include <vector>

#include "core/grid.hpp"
#include "geo/heightfield_source.hpp"

namespace tw {

struct HeightSamplerOptions {
  int block = 256;  // cells per block side; at most 16 on a generated world (computed cells)
  std::int64_t max_bytes = std::int64_t(64) << 20;  // cached heights; at least one block stays
};

// Not thread-safe: one per thread (the source is shared).
class HeightSampler {
 public:
  explicit HeightSampler(const HeightfieldSource& source, HeightSamplerOptions options = {});

  const GridSpec& grid() const { return source_.grid(); }
  // Height of a cell of the grid; NaN for nodata and off the grid.
  float cell(int col, int row);
  // sample_height_bilinear (geo/resample.hpp) over the whole heightfield.
  double bilinear(Vec2 world);

  std::int64_t blocks_read() const { return blocks_read_; }
  std::int64_t peak_bytes() const { return peak_bytes_; }

 private:
  struct Block {
    std::int64_t key = -1;
    Raster<float> cells;
  };
  const Block& block_at(int block_col, int block_row);

  const HeightfieldSource& source_;
  HeightSamplerOptions options_;
  int blocks_across_ = 0;
  std::list<Block> blocks_;  // most recently used first
  std::unordered_map<std::int64_t, std::list<Block>::iterator> index_;
  std::int64_t bytes_ = 0, peak_bytes_ = 0, blocks_read_ = 0;
};

}  // namespace tw
