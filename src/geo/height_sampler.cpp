#include "geo/height_sampler.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "geo/detail/cell_sampling.hpp"
#include "geo/detail/generated_source.hpp"

namespace tw {

HeightSampler::HeightSampler(const HeightfieldSource& source, HeightSamplerOptions options)
    : source_(source), options_(options) {
  // A generated world's cells are computed, not read: small blocks (see generated_source.hpp).
  if (detail::is_generated_source(source))
    options_.block = std::min(options_.block, detail::kGeneratedSampleBlock);
  if (options_.block < 1) fail("{}: height sampler block must be >= 1", source.name());
  blocks_across_ = (source.grid().width + options_.block - 1) / options_.block;
}

const HeightSampler::Block& HeightSampler::block_at(int block_col, int block_row) {
  const std::int64_t key = std::int64_t(block_row) * blocks_across_ + block_col;
  if (!blocks_.empty() && blocks_.front().key == key) return blocks_.front();
  if (const auto it = index_.find(key); it != index_.end()) {
    blocks_.splice(blocks_.begin(), blocks_, it->second);
    return blocks_.front();
  }
  const GridSpec& g = source_.grid();
  const int col0 = block_col * options_.block, row0 = block_row * options_.block;
  const Window window{col0, row0, std::min(options_.block, g.width - col0),
                      std::min(options_.block, g.height - row0)};
  const std::int64_t size =
      std::int64_t(window.width) * window.height * std::int64_t(sizeof(float));
  while (!blocks_.empty() && bytes_ + size > options_.max_bytes) {
    bytes_ -= std::int64_t(blocks_.back().cells.pixels.size() * sizeof(float));
    index_.erase(blocks_.back().key);
    blocks_.pop_back();
  }
  blocks_.push_front({key, source_.read(window)});
  index_[key] = blocks_.begin();
  bytes_ += size;
  peak_bytes_ = std::max(peak_bytes_, bytes_);
  ++blocks_read_;
  return blocks_.front();
}

float HeightSampler::cell(int col, int row) {
  const GridSpec& g = source_.grid();
  if (col < 0 || row < 0 || col >= g.width || row >= g.height)
    return std::numeric_limits<float>::quiet_NaN();
  const Block& b = block_at(col / options_.block, row / options_.block);
  return b.cells.at(col % options_.block, row % options_.block);
}

double HeightSampler::bilinear(Vec2 world) {
  return detail::bilinear_at([this](int col, int row) { return cell(col, row); }, grid(), world);
}

}  // namespace tw
