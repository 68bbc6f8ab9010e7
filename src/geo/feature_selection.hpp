#pragma once
// Which features of a layer an OGR SQL attribute filter selects, by FID: the predicate is OGR's
// (the same filter as reading a class), so any clause OGR accepts behaves as it does there.
#include <cstdint>
#include <vector>

#include "geo/features.hpp"

namespace tw {

// The FIDs (ascending) of the features of source's layer that source.where selects (every
// feature when it is empty). Throws tw::Error naming the file, the layer or the clause, as
// read_line_features does.
std::vector<std::int64_t> selected_fids(const VectorSource& source);

}  // namespace tw
