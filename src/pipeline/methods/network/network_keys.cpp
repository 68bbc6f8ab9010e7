// The network classes' keys of a pipeline file (docs/networks.md, "In pipelines"): a line
// class's `network:` block, and the region polygons it shares with `grow.region` (the block
// stands here, after `network`, in the schema's order).
#include "network/growth.hpp"
#include "pipeline/detail/key_forms.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/methods/network/network_method.hpp"

namespace tw::detail {

MethodKeys network_keys() {
  using namespace key_forms;
  return {
      {
          {"line_class",
           "grow",
           {"network",
            {block("network")},
            "grow the class's lines as a curve network by example (docs/networks.md)"}},
      },
      {
          {"network",
           "Grow the class's lines as a curve network in the style of an exemplar "
           "(docs/networks.md).",
           {
               {"exemplar",
                {path()},
                "the exemplar network: path[:layer] of lines or polygons, or an .svg",
                no_default(),
                required},
               {"exemplar_where", {string()}, "OGR SQL on the exemplar's layer"},
               {"exemplar_region", {path()}, "polygons cutting the exemplar from a larger map"},
               {"scale", {positive()}, "metres per SVG unit"},
               {"region",
                {{.type = ValueType::number_list, .count = 4}, block("grow_region")},
                "[minx, miny, maxx, maxy] or {source, layer, where} in the heightfield's CRS",
                no_default(),
                required},
               {"partial", {path()}, "lines already drawn, kept exactly and completed"},
               {"seed", {uint64()}, "default: the pipeline's"},
               {"lead",
                {choice({"long_axis", "nearest_road", "contours"}), block("lead")},
                "the direction the exemplar's main bearing is turned to over the region"},
               {"lead_bearing",
                {{.type = ValueType::number,
                  .minimum = 0.0,
                  .maximum = 360.0,
                  .exclusive_maximum = true}},
                "compass degrees the exemplar's main bearing is turned to (lead: {bearing})"},
               {"clearance", {non_negative()}, "metres between curves; 0: 6 % of the median edge"},
               {"snap",
                {non_negative()},
                "metres within which a growing end is pulled onto the network; 0: 35 % of the "
                "median edge"},
               {"candidates",
                {integer(1, 1000)},
                "pieces tried per open end",
                def(NetworkGrowthOptions{}.candidates)},
               {"method",
                {choice({kNetworkMethodNames.begin(), kNetworkMethodNames.end()})},
                "growth, quilt, layout (growth from the exemplar's long strokes), or automatic: "
                "each, and the one meeting the most quality targets (growth with `partial`)",
                def_text("automatic")},
               {"avoid",
                {boolean()},
                "keep off the existing features and the classes placed before",
                def_bool(true)},
           }},
          {"grow_region",
           "The polygons grown over.",
           {
               {"source", {path()}, "any vector data set OGR reads", no_default(), required},
               {"layer", {string()}, "layer name"},
               {"where", {string()}, "OGR SQL attribute filter"},
           }},
      },
  };
}

}  // namespace tw::detail
