#include "geo/heightfield.hpp"

#include "core/error.hpp"

namespace tw {

Heightfield read_heightfield(const std::string& path, const HeightfieldOptions&) {
  fail("{}: read_heightfield is not implemented yet", path);
}

}  // namespace tw
