#pragma once
// The safety net after growth (docs/networks.md, "Guarantees"), checked by GEOS independently of
// growth's own predicates: curves meet only at shared nodes, lie in the region and off forbidden
// cells. Every count is 0 unless growth has a bug; the command writes nothing otherwise.
#include <cstdint>
#include <string>
#include <vector>

#include "network/growth.hpp"

namespace tw {

struct NetworkCheck {
  std::int64_t crossings = 0;  // pairs of edges meeting elsewhere than at a common node
  std::int64_t outside = 0;    // edges not covered by the region (within 1e-6 of its scale)
  std::int64_t forbidden = 0;  // edges through a forbidden cell
  std::string first;           // the first problem, for the message
  std::int64_t total() const { return crossings + outside + forbidden; }
};

NetworkCheck check_network(const Network& network, const std::vector<Polygon>& region,
                           const ForbiddenMask* forbidden);

}  // namespace tw
