#pragma once
// The closed cells of a growing network as GEOS polygonize finds them (network_stats' cells), kept
// up to date while the cells are split and merged (docs/networks.md, "Growth", steps 9 and 10):
// found once over the whole network, then each edit changes only the cells it touches (ring
// surgery on their cycles of directed edges), so that a round costs the cells it edits, not the
// network. Internal to the network module.

#include <deque>
#include <vector>

#include "network/network.hpp"

namespace tw::network_detail {

class CellCycles {
 public:
  struct Cell {
    // Its outer ring's directed edges (2 e: along edge e's points, 2 e + 1: against them), from
    // the least: where polygonize starts the ring.
    std::vector<int> cycle;
    std::vector<std::vector<Vec2>> rings;  // outer first, closed, as polygonize writes them
    Vec2 lo, hi;                           // the outer ring's box
    double area = 0.0;                     // as OGR measures the polygon
  };

  // The network's edges, which of them are alive and each node's edges (alive or not): read at
  // each call, edited by the grower in between (every edit told here, see below).
  CellCycles(const Network& network, const std::vector<char>& alive,
             const std::vector<std::vector<int>>& incident)
      : network_(network), alive_(alive), incident_(incident) {}

  // The cells in polygonize's order (by their least directed edge), as polygonize over every
  // alive edge would give them now. The pointers last until the next edit.
  std::vector<const Cell*> cells();

  // The edits, each told right after it is made: edge `id` split at a new node, its far part
  // the new edge `second`; a new edge `id` (a chord) between two nodes of one cell; the edges of
  // a line between two cells taken off. An edit the cells cannot follow (it touches a cell with
  // holes, a line no cell has, ...) has them found again over the whole network.
  void edge_split(int id, int second);
  void chord_added(int id);
  void line_taken_off(const std::vector<int>& edges);

  // The cells found last and every edit since followed (cells() needs no polygonize).
  bool following() const { return found_ && network_.edges.size() == known_edges_; }

 private:
  void find_all();
  int end_node(int de) const;
  void write_rings(Cell& cell) const;
  int new_cell();
  void own(int cell);
  bool split_by_chord(int cell, int chord);

  const Network& network_;
  const std::vector<char>& alive_;
  const std::vector<std::vector<int>>& incident_;
  std::deque<Cell> store_;   // by slot (a deque: pointers stay valid as it grows)
  std::vector<char> live_;   // per slot
  std::vector<int> free_;    // slots to reuse
  std::vector<int> owner_;   // per directed edge: the slot whose outer ring or hole has it, or -1
  std::vector<char> holed_;  // per slot: it has holes (an edit touching it finds all again)
  std::vector<char> dirty_;  // per slot: its rings are to be written again from its cycle
  std::size_t known_edges_ = 0;  // the edges it has seen (an edit not told is one more)
  bool found_ = false;           // the cells were found and followed every edit since
  bool incremental_ = true;      // polygonize's rings map onto cycles (else found every time)
};

}  // namespace tw::network_detail
