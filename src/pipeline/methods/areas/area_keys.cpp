// The area classes' keys of a pipeline file (docs/shape-patterns.md): a `kind: area` class (its
// `lead` block is the pipeline's own, shared with the network classes).
#include "pipeline/detail/key_forms.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/methods/areas/area_method.hpp"

namespace tw::detail {

MethodKeys area_keys() {
  using namespace key_forms;
  return {
      {},
      {
          {"area_class",
           "A kind: area class: polygons filled with a structured shape-pattern "
           "(docs/shape-patterns.md).",
           {
               {"kind", {choice({"area"})}, "area", no_default(), required},
               {"source",
                {path()},
                "polygons, any vector data set OGR reads",
                no_default(),
                required},
               {"layer", {string()}, "layer name"},
               {"where", {string()}, "OGR SQL attribute filter"},
               {"tags", {of(ValueType::tags)}, "OSM-style selection"},
               {"sketch", {path()}, "strokes in [0,1]^2", no_default(), required},
               {"shapes_from", {path()}, "a second sketch whose shapes go on the first one's rows"},
               {"scale", {positive()}, "metres per sketch unit"},
               {"lead",
                {choice({"long_axis", "nearest_road", "contours"}), block("lead")},
                "direction of the sketch's x axis"},
               {"jitter", {number(0.0, 1.0)}, "fraction of each allowed displacement"},
               {"materials",
                {of(ValueType::map_string)},
                "sketch stroke material -> splat material"},
               {"height",
                {{.type = ValueType::map_number, .minimum = -100.0, .maximum = 100.0}},
                "sketch stroke material -> metres"},
               {"seed", {uint64()}, "default: the pipeline's"},
           }},
      },
  };
}

}  // namespace tw::detail
