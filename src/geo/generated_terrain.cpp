#include "core/error.hpp"
#include "geo/heightfield.hpp"

namespace tw {

Heightfield generate_heightfield(const GeneratedTerrain& params) {
  fail("generate_heightfield(seed={}) is not implemented yet", params.seed);
}

}  // namespace tw
