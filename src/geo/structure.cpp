#include "geo/structure.hpp"

namespace tw {

std::string_view to_string(Structure structure) {
  switch (structure) {
    case Structure::ground:
      return "ground";
    case Structure::bridge:
      return "bridge";
    case Structure::tunnel:
      return "tunnel";
  }
  return "unknown";
}

bool meet_at_grade(Structure a, int layer_a, Structure b, int layer_b) {
  return a == Structure::ground && b == Structure::ground && layer_a == layer_b;
}

}  // namespace tw
