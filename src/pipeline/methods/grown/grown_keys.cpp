// The grown classes' keys of a pipeline file (docs/ornaments.md): a line class's `grow:` block.
#include "pipeline/detail/key_forms.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/grow_config.hpp"
#include "pipeline/methods/grown/grown_method.hpp"

namespace tw::detail {

MethodKeys grown_keys() {
  using namespace key_forms;
  const GrowSettings grow;
  return {
      {
          {"line_class",
           "repair",
           {"grow", {block("grow")}, "grow the class's lines (FloralSurf, docs/ornaments.md)"}},
      },
      {
          {"grow",
           "Grow the class's lines over a region (FloralSurf, docs/ornaments.md).",
           {
               {"element",
                {path()},
                "element set (samples/ornaments/*.json)",
                no_default(),
                required},
               {"region",
                {{.type = ValueType::number_list, .count = 4}, block("grow_region")},
                "[minx, miny, maxx, maxy] or {source, layer, where}; default: the class's source"},
               {"resolution", {positive()}, "metres between mesh vertices; default: the DEM's"},
               {"seed", {uint64()}, "default: the pipeline's"},
               {"alignment",
                {choice({"growth", "contour"})},
                "element direction",
                def_text("growth")},
               {"first_fit", {boolean()}, "the greedy variant", def_bool(grow.first_fit)},
               {"trials", {integer(1, 1000)}, "candidates per growth point", def(grow.trials)},
               {"max_ornaments",
                {integer(1, 100000)},
                "ornaments started at most",
                def(grow.max_ornaments)},
               {"max_elements",
                {integer(1, 10000000)},
                "elements placed at most",
                def(grow.max_elements)},
               {"coverage_radius", {positive()}, "metres for the reported coverage"},
               {"clearance", {non_negative()}, "metres between unrelated lines"},
           }},
      },
  };
}

}  // namespace tw::detail
