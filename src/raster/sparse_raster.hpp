#pragma once
// A sparse tiled raster over a grid: square tiles of `tile_size` cells, allocated only where a
// caller asks (e.g. where a ribbon and its halo pass), every other cell reading `background`.
// Memory is the allocated tiles plus a directory of one int per tile of the grid, so a canvas
// around a 100 km river costs its ribbon's length x width, not its bounding box.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "ribbon/ribbon.hpp"

namespace tw {

struct TileIndex {
  int tx = 0;
  int ty = 0;
  friend constexpr bool operator==(const TileIndex&, const TileIndex&) = default;
};

template <class T>
class SparseRaster {
 public:
  static constexpr int kDefaultTileSize = 256;

  SparseRaster() = default;
  // `tile_size` <= 0 or >= both sides: one tile covering the whole raster (a dense canvas).
  SparseRaster(int width, int height, T background = T{}, int tile_size = kDefaultTileSize)
      : width_(width), height_(height), background_(background) {
    tile_size_ = tile_size <= 0 ? std::max({width, height, 1}) : tile_size;
    tiles_x_ = (width + tile_size_ - 1) / tile_size_;
    tiles_y_ = (height + tile_size_ - 1) / tile_size_;
    slots_.assign(std::size_t(tiles_x_) * tiles_y_, -1);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int tile_size() const { return tile_size_; }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  T background() const { return background_; }
  bool inside(int col, int row) const {
    return col >= 0 && row >= 0 && col < width_ && row < height_;
  }

  // The cell, or `background` outside the raster or in a tile never allocated.
  T at(int col, int row) const {
    if (!inside(col, row)) return background_;
    const std::int32_t slot = slots_[slot_of(col / tile_size_, row / tile_size_)];
    if (slot < 0) return background_;
    const Raster<T>& tile = tiles_[std::size_t(slot)];
    return tile.at(col % tile_size_, row % tile_size_);
  }
  // Sets a cell inside the raster, allocating its tile.
  void set(int col, int row, T value) {
    add_tile({col / tile_size_, row / tile_size_}).at(col % tile_size_, row % tile_size_) = value;
  }

  // The cells of a tile (clipped to the raster at its right and bottom edges).
  Window tile_window(TileIndex t) const {
    const int col0 = t.tx * tile_size_, row0 = t.ty * tile_size_;
    return {col0, row0, std::min(tile_size_, width_ - col0), std::min(tile_size_, height_ - row0)};
  }
  bool has_tile(TileIndex t) const { return slots_[slot_of(t.tx, t.ty)] >= 0; }
  // The tile's cells (tile_window-sized), or null when it is not allocated.
  const Raster<T>* tile(TileIndex t) const {
    const std::int32_t slot = slots_[slot_of(t.tx, t.ty)];
    return slot < 0 ? nullptr : &tiles_[std::size_t(slot)];
  }
  Raster<T>* tile(TileIndex t) {
    const std::int32_t slot = slots_[slot_of(t.tx, t.ty)];
    return slot < 0 ? nullptr : &tiles_[std::size_t(slot)];
  }
  // Allocates the tile filled with `background` when absent; returns its cells.
  Raster<T>& add_tile(TileIndex t) {
    std::int32_t& slot = slots_[slot_of(t.tx, t.ty)];
    if (slot < 0) {
      const Window w = tile_window(t);
      slot = std::int32_t(tiles_.size());
      tiles_.emplace_back(w.width, w.height, background_);
      indices_.push_back(t);
    }
    return tiles_[std::size_t(slot)];
  }

  // Frees the tiles whose every cell reads `background` (nobody needs them: they read the same
  // unallocated); the others keep their order.
  void drop_background_tiles() {
    std::vector<Raster<T>> kept;
    std::vector<TileIndex> kept_indices;
    for (std::size_t k = 0; k < tiles_.size(); ++k) {
      const auto& cells = tiles_[k].pixels;
      const bool blank =
          std::all_of(cells.begin(), cells.end(), [&](T v) { return v == background_; });
      slots_[slot_of(indices_[k].tx, indices_[k].ty)] = blank ? -1 : std::int32_t(kept.size());
      if (blank) continue;
      kept.push_back(std::move(tiles_[k]));
      kept_indices.push_back(indices_[k]);
    }
    tiles_ = std::move(kept);
    indices_ = std::move(kept_indices);
  }

  // Allocated tiles, in the order they were added.
  const std::vector<TileIndex>& tiles() const { return indices_; }
  std::size_t tile_count() const { return indices_.size(); }
  // Bytes of cells held (the directory adds 4 bytes per tile of the grid).
  std::size_t allocated_bytes() const {
    std::size_t bytes = slots_.size() * sizeof(std::int32_t);
    for (const Raster<T>& tile : tiles_) bytes += tile.pixels.size() * sizeof(T);
    return bytes;
  }

 private:
  std::size_t slot_of(int tx, int ty) const { return std::size_t(ty) * tiles_x_ + tx; }

  int width_ = 0, height_ = 0, tile_size_ = kDefaultTileSize, tiles_x_ = 0, tiles_y_ = 0;
  T background_{};
  std::vector<std::int32_t> slots_;  // per tile of the grid: index into tiles_, -1 if absent
  std::vector<Raster<T>> tiles_;
  std::vector<TileIndex> indices_;  // of tiles_, same order
};

// The tiles of `raster` that meet the pixel box of a ribbon piece grown by `halo` pixels, for
// every piece, in row-major order without repeats.
std::vector<TileIndex> ribbon_tiles(const Ribbon& ribbon, const GridSpec& grid, int tile_size,
                                    int halo);

// Allocates `tiles` in `raster` (those already there stay as they are).
template <class T>
void add_tiles(SparseRaster<T>& raster, const std::vector<TileIndex>& tiles) {
  for (const TileIndex t : tiles) raster.add_tile(t);
}

// Sets 1 on the allocated cells of `target` (over `target_grid`) where `source` (over
// `source_grid`) is non-zero. Both grids lie on one lattice: the same cell size, origins a whole
// number of cells apart. Cells of absent target tiles are skipped (nobody reads them).
void add_on_lattice(const SparseRaster<std::uint8_t>& source, const GridSpec& source_grid,
                    SparseRaster<std::uint8_t>& target, const GridSpec& target_grid);

// Sets `value` where a cell centre of an allocated tile of `target` (over `grid`) lies within
// widths[i] / 2 of lines[i] (burn_buffered_lines' exact buffers, tile by tile: each line is burnt
// only on the allocated tiles its box meets, so a million short strokes cost their own cells).
void burn_buffered_lines_on(const std::vector<const std::vector<Vec2>*>& lines,
                            const std::vector<double>& widths, const GridSpec& grid,
                            SparseRaster<std::uint8_t>& target, std::uint8_t value);

// A sparse copy of a dense raster: only tiles holding a cell other than `background`.
template <class T>
SparseRaster<T> sparse_from_dense(const Raster<T>& dense, T background = T{},
                                  int tile_size = SparseRaster<T>::kDefaultTileSize) {
  SparseRaster<T> sparse(dense.width, dense.height, background, tile_size);
  for (int ty = 0; ty < sparse.tiles_y(); ++ty)
    for (int tx = 0; tx < sparse.tiles_x(); ++tx) {
      const Window w = sparse.tile_window({tx, ty});
      for (int row = w.row0; row < w.row_end(); ++row)
        for (int col = w.col0; col < w.col_end(); ++col)
          if (dense.at(col, row) != background) sparse.set(col, row, dense.at(col, row));
    }
  return sparse;
}

}  // namespace tw
