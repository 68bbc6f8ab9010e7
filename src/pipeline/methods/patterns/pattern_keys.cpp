// The patterns' keys of a pipeline file (docs/patterns.md): the canvas and the order at the top
// level, a line class's `synthesis:` block and its bindings.
#include "pipeline/config.hpp"
#include "pipeline/detail/key_forms.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"

namespace tw::detail {

MethodKeys pattern_keys() {
  using namespace key_forms;
  const SynthesisConfig synthesis;
  const PipelineConfig pipeline;
  const double W = kMaxFeatureWidth;
  return {
      {
          {"root",
           "existing",
           {"synthesis_resolution",
            {positive()},
            "metres per cell of the synthesis canvas",
            def(pipeline.synthesis_resolution)}},
          {"root",
           "synthesis_resolution",
           {"synthesis_order",
            {of(ValueType::string_list)},
            "the order of synthesis; every class with synthesis once"}},
          {"line_class",
           "conform",
           {"synthesis", {block("synthesis")}, "pattern synthesis along the class"}},
      },
      {
          {"synthesis",
           "Pattern synthesis along every feature of the class (docs/patterns.md).",
           {
               {"exemplar",
                {path(), of(ValueType::path_list)},
                "RGBA images (OIIO)",
                no_default(),
                required},
               {"choose",
                {choice({"seed", "best", "mix"})},
                "how several exemplars are used",
                def_text("seed")},
               {"switch_cost",
                {integer(0, 1 << 20)},
                "choose: mix only: colour units per switch",
                def(synthesis.switch_cost)},
               {"bind",
                {{.type = ValueType::block_list, .block = "binding", .count = 1}},
                "choose: mix only: pieces bound to exemplars"},
               {"width",
                {positive(W), choice({"feature"})},
                "ribbon width in metres, or feature; default: from the exemplar"},
               {"delta", {positive()}, "piece length in metres; default: from the exemplar"},
               {"scale", {positive()}, "exemplar texels per metre", def(synthesis.scale)},
               {"stitch", {boolean()}, "the paper's seam stitching", def_bool(synthesis.stitch)},
               {"empty_pieces",
                {boolean()},
                "a piece with no valid position stays transparent",
                def_bool(synthesis.empty_pieces)},
               {"min_coverage",
                {{.type = ValueType::number,
                  .minimum = 0.0,
                  .maximum = 1.0,
                  .exclusive_maximum = true}},
                "opaque fraction of each piece at a valid position; default: from the exemplar"},
               {"objective",
                {choice({"pattern", "paper"})},
                "what the DP minimizes",
                def_text("pattern")},
               {"coverage_weight",
                {non_negative()},
                "objective: pattern's coverage weight",
                def(synthesis.coverage_weight)},
               {"alpha",
                {choice({"binary", "continuous"})},
                "how the matching cost reads alpha",
                def_text("binary")},
               {"feather",
                {non_negative()},
                "metres of blending at each seam",
                def(synthesis.feather)},
               {"seed", {uint64()}, "the class seed; default: the pipeline's"},
               {"backend", {choice(kBackends)}, "default: the pipeline's"},
               {"height_detail",
                {non_negative()},
                "factor on the height channel",
                def(synthesis.height_detail)},
               {"channels",
                {of(ValueType::channels)},
                "exemplar channel -> height or splat.<material>"},
           }},
          {"binding",
           "choose: mix: a rule binding pieces to one exemplar.",
           {
               {"exemplar",
                {string(), integer(0)},
                "one of the class's exemplar paths or its index",
                no_default(),
                required},
               {"where", {string()}, "OGR SQL on the class's layer"},
               {"tags", {of(ValueType::tags)}, "OSM-style selection"},
               {"near_junction", {non_negative(W)}, "metres from a junction"},
           }},
      },
  };
}

}  // namespace tw::detail
