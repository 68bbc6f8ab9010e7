#pragma once
// The world's ribbons as one binary object of the plan folder (plan_io), readable in part: a
// render-tile decodes only the ribbons that can reach its tile (WorldPlan::ribbon_index), not
// the world's (issue #23 item 4). After the header of every binary object (plan_objects):
//   uint64 classes, then uint64 ribbons per class
//   uint64 offsets[ribbons + 1]  where each ribbon's bytes start, from the first ribbon's
//   the ribbons, class-major (the order of ribbon_index), each as plan_binary.hpp writes it
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ribbon/ribbon.hpp"

namespace tw::detail {

std::string ribbons_to_bytes(const std::vector<std::vector<Ribbon>>& ribbons);

// Every ribbon, or with `only` (class-major indices, sorted) those alone: the others keep their
// class and place but are empty (no centerline, no pieces). Throws tw::Error naming `where` on
// bytes that do not hold ribbons.
void ribbons_from_bytes(std::string_view bytes, std::vector<std::vector<Ribbon>>& ribbons,
                        const std::vector<std::size_t>* only, const std::string& where);

}  // namespace tw::detail
