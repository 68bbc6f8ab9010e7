// The cells as the grower keeps them while it splits and merges them (docs/networks.md, "Speed"):
// after a chord or a line taken off, the same rings, in the same order, with the same areas as
// GEOS polygonize finds over the whole network.
#include <gtest/gtest.h>

#include <algorithm>

#include "network/detail/cell_cycles.hpp"

namespace tw {
namespace {

using network_detail::CellCycles;

// A network edited as the grower edits its own (Grower::split_edge, link_to, take_off).
struct CellCycleNetwork {
  Network net;
  std::vector<char> alive;
  std::vector<std::vector<int>> incident;

  int node(Vec2 p) {
    net.nodes.push_back(p);
    incident.emplace_back();
    return int(net.nodes.size()) - 1;
  }
  int edge(int from, int to) {
    net.edges.push_back({.from = from,
                         .to = to,
                         .points = {net.nodes[std::size_t(from)], net.nodes[std::size_t(to)]}});
    alive.push_back(1);
    const int id = int(net.edges.size()) - 1;
    incident[std::size_t(from)].push_back(id);
    incident[std::size_t(to)].push_back(id);
    return id;
  }
  // Edge `id` (two points) split at p: it keeps the part from its start, a new edge the rest.
  int split(int id, Vec2 p) {
    const int n = node(p), to = net.edges[std::size_t(id)].to;
    std::erase(incident[std::size_t(to)], id);
    net.edges[std::size_t(id)].to = n;
    net.edges[std::size_t(id)].points.back() = p;
    incident[std::size_t(n)].push_back(id);
    edge(n, to);
    return n;
  }
};

// A grid of 3 × 3 square cells 100 m a side; the edges between nodes (i, j) and (i + 1, j)
// are h[i][j], those between (i, j) and (i, j + 1) are v[i][j].
struct CellCycleGrid {
  CellCycleNetwork g;
  int h[3][4], v[4][3];
  CellCycleGrid() {
    int at[4][4];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) at[i][j] = g.node({100.0 * i, 100.0 * j});
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) h[i][j] = g.edge(at[i][j], at[i + 1][j]);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) v[i][j] = g.edge(at[i][j], at[i][j + 1]);
  }
};

// The cells kept through the edits are those polygonize finds now, ring for ring.
void expect_as_polygonize_finds(CellCycles& kept, const CellCycleNetwork& g) {
  CellCycles found(g.net, g.alive, g.incident);
  const std::vector<const CellCycles::Cell*> a = kept.cells(), b = found.cells();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_TRUE(a[k]->rings == b[k]->rings) << k;
    EXPECT_EQ(a[k]->area, b[k]->area) << k;
    EXPECT_TRUE(a[k]->lo == b[k]->lo && a[k]->hi == b[k]->hi) << k;
  }
}

std::vector<double> cell_cycle_areas(CellCycles& cells) {
  std::vector<double> out;
  for (const CellCycles::Cell* c : cells.cells()) out.push_back(c->area);
  std::sort(out.begin(), out.end());
  return out;
}

// The middle cell split from its bottom side to its top side by a chord, as split_large_cells
// does: both sides split at their middle, each edit told.
void split_middle_cell(CellCycleGrid& grid, CellCycles& cells) {
  CellCycleNetwork& g = grid.g;
  const int p = g.split(grid.h[1][1], {150.0, 100.0});
  cells.edge_split(grid.h[1][1], int(g.net.edges.size()) - 1);
  const int q = g.split(grid.h[1][2], {150.0, 200.0});
  cells.edge_split(grid.h[1][2], int(g.net.edges.size()) - 1);
  g.edge(p, q);
  cells.chord_added(int(g.net.edges.size()) - 1);
}

TEST(NetworkCellCycles, AChordSplitsOneCellAsPolygonizeWould) {
  CellCycleGrid grid;
  CellCycleNetwork& g = grid.g;
  CellCycles cells(g.net, g.alive, g.incident);
  EXPECT_EQ(cell_cycle_areas(cells), std::vector<double>(9, 1e4));
  split_middle_cell(grid, cells);
  EXPECT_TRUE(cells.following());
  std::vector<double> want(8, 1e4);
  want.insert(want.begin(), {5e3, 5e3});
  EXPECT_EQ(cell_cycle_areas(cells), want);
  expect_as_polygonize_finds(cells, g);
}

TEST(NetworkCellCycles, ALineTakenOffMergesItsTwoCellsAsPolygonizeWould) {
  CellCycleGrid grid;
  CellCycleNetwork& g = grid.g;
  CellCycles cells(g.net, g.alive, g.incident);
  cells.cells();
  // The line between the bottom left cell and the one right of it, as merge_small_cells does.
  g.alive[std::size_t(grid.v[1][0])] = 0;
  cells.line_taken_off({grid.v[1][0]});
  EXPECT_TRUE(cells.following());
  std::vector<double> want(7, 1e4);
  want.push_back(2e4);
  EXPECT_EQ(cell_cycle_areas(cells), want);
  expect_as_polygonize_finds(cells, g);
  // Then the middle cell split: the merged cell's cycle is split-able as any other.
  split_middle_cell(grid, cells);
  EXPECT_TRUE(cells.following());
  expect_as_polygonize_finds(cells, g);
}

// An edit no cell's cycle can follow (a line on the network's outside: one cell beside it) has
// the cells found again over the whole network.
TEST(NetworkCellCycles, AnEditItCannotFollowHasTheCellsFoundAgain) {
  CellCycleGrid grid;
  CellCycleNetwork& g = grid.g;
  CellCycles cells(g.net, g.alive, g.incident);
  cells.cells();
  g.alive[std::size_t(grid.h[0][0])] = 0;
  cells.line_taken_off({grid.h[0][0]});
  EXPECT_FALSE(cells.following());
  EXPECT_EQ(cell_cycle_areas(cells), std::vector<double>(8, 1e4));
  expect_as_polygonize_finds(cells, g);
}

}  // namespace
}  // namespace tw
