#include "pipeline/detail/pipeline_keys.hpp"

#include <stdexcept>
#include <string>

#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "network/growth.hpp"
#include "pipeline/config.hpp"
#include "pipeline/grow_config.hpp"
#include "terrain/features.hpp"

namespace tw::detail {

namespace {

// The forms a key's value may take (the table below reads as the docs' key tables).
ValueForm number(double lo = -std::numeric_limits<double>::infinity(),
                 double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::number, .minimum = lo, .maximum = hi};
}
ValueForm positive(double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::number, .minimum = 0.0, .maximum = hi, .exclusive_minimum = true};
}
ValueForm non_negative(double hi = std::numeric_limits<double>::infinity()) {
  return number(0.0, hi);
}
ValueForm integer(double lo, double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::integer, .minimum = lo, .maximum = hi};
}
ValueForm uint64() {
  return integer(0.0);
}
ValueForm boolean() {
  return {.type = ValueType::boolean};
}
ValueForm string() {
  return {.type = ValueType::string};
}
ValueForm path() {
  return {.type = ValueType::path};
}
ValueForm choice(std::vector<std::string_view> values) {
  return {.type = ValueType::choice, .values = std::move(values)};
}
ValueForm block(std::string_view name) {
  return {.type = ValueType::block, .block = name};
}
ValueForm of(ValueType type) {
  return {.type = type};
}

KeyDefault no_default() {
  return {};
}
KeyDefault def(double value) {
  return {.kind = KeyDefault::Kind::number, .number = value};
}
KeyDefault def_bool(bool value) {
  return {.kind = KeyDefault::Kind::boolean, .boolean = value};
}
KeyDefault def_text(std::string_view text) {
  return {.kind = KeyDefault::Kind::text, .text = text};
}

constexpr bool required = true;

const std::vector<std::string_view> kBackends{"cpu", "opencl", "auto"};
const std::vector<std::string_view> kEngines{"unreal", "unity", "godot", "terrain3d"};

std::vector<KeyBlock> make_blocks() {
  const RoadProfile road;
  const RiverProfile river;
  const RidgeProfile ridge;
  const LineRepair repair;
  const GrowSettings grow;
  const GenerateConfig generate;
  const OutputConfig output;
  const SynthesisConfig synthesis;
  const PipelineConfig pipeline;
  const double W = kMaxFeatureWidth;
  const double H = kMaxAbsHeight;
  return {
      {"root",
       "A terraweave pipeline file (docs/pipeline.md).",
       {
           {"version", {integer(1, 1)}, "must be 1", no_default(), required},
           {"seed",
            {uint64()},
            "seeds the generated terrain and, by default, every synthesis",
            def(double(pipeline.seed))},
           {"heightfield", {path()}, "any raster GDAL reads (band 1, metres); omit to generate"},
           {"generate",
            {block("generate")},
            "a seeded fractal terrain; not together with heightfield"},
           {"resolution", {positive()}, "output pixel size in metres; default: the source's"},
           {"output", {block("output")}, "what is written where"},
           {"backend", {choice(kBackends)}, "synthesis backend", def_text("auto")},
           {"precedence",
            {of(ValueType::string_list)},
            "the order in which line classes apply (later wins); every line class once"},
           {"features",
            {of(ValueType::feature_classes)},
            "feature classes by name ([A-Za-z_][A-Za-z0-9_-]*), at least one",
            no_default(),
            required},
           {"existing",
            {{.type = ValueType::block_list, .block = "existing"}},
            "avoidance inputs: features no synthesis may cover"},
           {"synthesis_resolution",
            {positive()},
            "metres per cell of the synthesis canvas",
            def(pipeline.synthesis_resolution)},
           {"synthesis_order",
            {of(ValueType::string_list)},
            "the order of synthesis; every class with synthesis once"},
           {"region",
            {{.type = ValueType::number_list, .count = 4}},
            "[min_x, min_y, max_x, max_y]: output only this rectangle (metres)"},
           {"resampling",
            {choice({"bilinear", "cubic"})},
            "how the heightfield is read between its cells",
            def_text("bilinear")},
           {"strict",
            {boolean()},
            "any warning fails the run before anything is written",
            def_bool(pipeline.strict)},
           {"repair", {block("repair")}, "how messy lines are cleaned"},
           {"avoidance", {block("avoidance")}, "the avoidance layer"},
           {"cache", {path()}, "folder where runs reuse syntheses and tiles (docs/cache.md)"},
           {"export",
            {{.type = ValueType::choice_list, .values = kEngines}, block("export_engines")},
            "engine exports (docs/exports.md): a list of engines or engine -> options"},
       }},
      {"generate",
       "A seeded fractal terrain.",
       {
           {"width", {integer(2, 65536)}, "cells", def(generate.width)},
           {"height", {integer(2, 65536)}, "cells", def(generate.height)},
           {"pixel_size", {positive()}, "metres per cell", def(generate.pixel_size)},
           {"relief",
            {non_negative(kMaxGeneratedRelief)},
            "metres between lowest and highest height",
            def(generate.relief)},
           {"crs", {string()}, "a projected CRS in metres", def_text("EPSG:32631")},
           {"origin",
            {{.type = ValueType::number_list, .count = 2}},
            "[x, y]: world position of the north-west corner"},
       }},
      {"output",
       "What is written where.",
       {
           {"dir", {path()}, "folder of the outputs (--out replaces it)", def_text("out")},
           {"formats",
            {{.type = ValueType::choice_list, .values = {"exr", "geotiff"}}},
            "the layer encodings written, each once; not together with exr / geotiff"},
           {"exr", {boolean()}, "write EXR layers", def_bool(output.exr)},
           {"geotiff", {boolean()}, "write GeoTIFF layers", def_bool(output.geotiff)},
           {"preview", {boolean()}, "write preview.png", def_bool(output.preview)},
           {"tiles", {block("tiles")}, "render and write in tiles (docs/tiles.md)"},
           {"exr_half",
            {boolean()},
            "true: every EXR channel a 16-bit half float; false: every one float32; absent: "
            "chosen per layer (splat weights half)"},
           {"exr_compression",
            {choice({"automatic", "none", "rle", "zips", "zip", "piz", "pxr24", "b44", "dwaa",
                     "dwab"})},
            "EXR codec of every layer; automatic: chosen per layer by its pixels",
            def_text("automatic")},
           {"compress",
            {choice({"zstd", "deflate", "lzw", "none"})},
            "GeoTIFF compression",
            def_text("zstd")},
           {"predictor",
            {choice({"none", "horizontal", "float"})},
            "GeoTIFF predictor",
            def_text("none")},
           {"cog", {boolean()}, "Cloud-Optimized GeoTIFFs", def_bool(output.tiff.cog)},
           {"overviews",
            {boolean()},
            "internal overviews on plain GeoTIFFs",
            def_bool(output.tiff.overviews)},
           {"crs", {string()}, "the CRS of every output: a CRS PROJ knows, utm or local"},
       }},
      {"tiles",
       "Tiles of size x size pixels, each with overlap more on every side.",
       {
           {"size", {integer(1, kMaxTileSize)}, "pixels per tile side", no_default(), required},
           {"overlap", {integer(0, kMaxTileOverlap)}, "pixels more on every side", def(0)},
       }},
      {"avoidance",
       "The avoidance layer.",
       {
           {"max_distance",
            {positive()},
            "metres: the cap of the distance band",
            def(pipeline.avoidance.max_distance)},
       }},
      {"repair",
       "How messy lines are cleaned; a class's own repair overrides the pipeline's key by key.",
       {
           {"merge_distance",
            {non_negative()},
            "consecutive vertices closer are one (metres)",
            def(repair.merge_distance)},
           {"min_loop",
            {non_negative()},
            "shorter loops are cut out (metres of line)",
            def(repair.min_loop)},
           {"spike_angle",
            {{.type = ValueType::number,
              .minimum = 0.0,
              .maximum = 180.0,
              .exclusive_minimum = true,
              .exclusive_maximum = true}},
            "degrees: a vertex turning back by more is a spike, removed",
            def(repair.spike_angle)},
       }},
      {"export_engines",
       "Engine exports by engine name.",
       {
           {"unreal", {of(ValueType::null_value), block("export_options")}, "Unreal Engine"},
           {"unity", {of(ValueType::null_value), block("export_options")}, "Unity"},
           {"godot", {of(ValueType::null_value), block("export_options")}, "Godot"},
           {"terrain3d", {of(ValueType::null_value), block("export_options")}, "Godot 4 Terrain3D"},
       }},
      {"export_options",
       "One engine's export options.",
       {
           {"size",
            {integer(0)},
            "heightmap samples per side (Unreal any from 8 to 8129; Unity/Godot 2^n + 1)"},
           {"nodata_height", {number()}, "metres written for nodata"},
           {"height", {choice({"exr", "r16"})}, "godot and terrain3d: the height format"},
           {"layers",
            {boolean()},
            "also the non-destructive layers (height delta, weight layers); untiled runs"},
           {"tile_size", {integer(0)}, "samples per tile, an engine size; 0 = one heightmap"},
       }},
      {"line_class",
       "A feature class of lines: read from source, or grown (grow).",
       {
           {"source", {path()}, "any vector data set OGR reads"},
           {"layer", {string()}, "layer name; default: the first"},
           {"where", {string()}, "OGR SQL attribute filter"},
           {"tags", {of(ValueType::tags)}, "OSM-style selection (docs/osm.md)"},
           {"kind",
            {choice({"road", "river", "ridge", "hedge", "wall", "trail", "ditch"})},
            "what the class does to the terrain; required unless tags imply it"},
           {"width_attribute", {string()}, "attribute holding each feature's width in metres"},
           {"width", {positive(W)}, "metres"},
           {"profile",
            {block("road_profile"), block("river_profile"), block("ridge_profile")},
            "the terrain profile; keys depend on kind"},
           {"conform", {block("conform")}, "rivers and ridges: move lines onto the DEM"},
           {"synthesis", {block("synthesis")}, "pattern synthesis along the class"},
           {"repair", {block("repair")}, "this class's repair, over the pipeline's"},
           {"grow", {block("grow")}, "grow the class's lines (FloralSurf, docs/ornaments.md)"},
           {"network",
            {block("network")},
            "grow the class's lines as a curve network by example (docs/networks.md)"},
       }},
      {"road_profile",
       "profile of kind: road (trail).",
       {
           {"max_grade", {positive()}, "rise over run", def(road.max_grade)},
           {"shoulder_width", {non_negative(W)}, "metres", def(road.shoulder_width)},
           {"falloff", {non_negative(W)}, "metres of cut/fill slope", def(road.falloff)},
           {"smoothing", {non_negative(W)}, "metres of along-road smoothing", def(road.smoothing)},
           {"max_cut", {non_negative(H)}, "metres the road may lie below the terrain"},
           {"max_fill", {non_negative(H)}, "metres the road may lie above the terrain"},
       }},
      {"river_profile",
       "profile of kind: river (ditch).",
       {
           {"depth", {non_negative(H)}, "metres of bed below the water surface", def(river.depth)},
           {"bank_width", {non_negative(W)}, "metres", def(river.bank_width)},
           {"falloff", {non_negative(W)}, "metres", def(river.falloff)},
           {"min_slope", {non_negative()}, "metres per metre downstream", def(river.min_slope)},
           {"max_carve", {non_negative()}, "metres; default: 2 x depth"},
       }},
      {"ridge_profile",
       "profile of kind: ridge (hedge, wall).",
       {
           {"height", {non_negative(H)}, "metres", def(ridge.height)},
           {"falloff", {non_negative(W)}, "metres", def(ridge.falloff)},
           {"sharpness", {positive()}, "crest sharpness", def(ridge.sharpness)},
       }},
      {"conform",
       "Move each line onto the DEM's valley floor (rivers) or crest (ridges).",
       {
           {"corridor", {positive()}, "metres either side of each line", no_default(), required},
       }},
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
           {"feather", {non_negative()}, "metres of blending at each seam", def(synthesis.feather)},
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
      {"grow",
       "Grow the class's lines over a region (FloralSurf, docs/ornaments.md).",
       {
           {"element", {path()}, "element set (samples/ornaments/*.json)", no_default(), required},
           {"region",
            {{.type = ValueType::number_list, .count = 4}, block("grow_region")},
            "[minx, miny, maxx, maxy] or {source, layer, where}; default: the class's source"},
           {"resolution", {positive()}, "metres between mesh vertices; default: the DEM's"},
           {"seed", {uint64()}, "default: the pipeline's"},
           {"alignment", {choice({"growth", "contour"})}, "element direction", def_text("growth")},
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
      {"network",
       "Grow the class's lines as a curve network in the style of an exemplar (docs/networks.md).",
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
           {"lead_bearing",
            {{.type = ValueType::number,
              .minimum = 0.0,
              .maximum = 360.0,
              .exclusive_maximum = true}},
            "compass degrees the exemplar's main bearing is turned to"},
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
            "growth, quilt, or automatic: both, and growth from the exemplar's long strokes, and "
            "the one meeting the most quality targets (growth with `partial`)",
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
      {"area_class",
       "A kind: area class: polygons filled with a structured shape-pattern "
       "(docs/shape-patterns.md).",
       {
           {"kind", {choice({"area"})}, "area", no_default(), required},
           {"source", {path()}, "polygons, any vector data set OGR reads", no_default(), required},
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
           {"materials", {of(ValueType::map_string)}, "sketch stroke material -> splat material"},
           {"height",
            {{.type = ValueType::map_number, .minimum = -100.0, .maximum = 100.0}},
            "sketch stroke material -> metres"},
           {"seed", {uint64()}, "default: the pipeline's"},
       }},
      {"lead",
       "A fixed direction.",
       {
           {"bearing", {number()}, "compass bearing in degrees", no_default(), required},
       }},
      {"existing",
       "Features no synthesis may cover.",
       {
           {"source", {path()}, "any vector data set OGR reads", no_default(), required},
           {"layer", {string()}, "layer name"},
           {"where", {string()}, "OGR SQL attribute filter"},
           {"tags", {of(ValueType::tags)}, "OSM-style selection"},
           {"width", {positive(W)}, "metres; required for lines"},
       }},
  };
}

}  // namespace

const KeySpec* KeyBlock::find(std::string_view key) const {
  for (const KeySpec& k : keys)
    if (k.name == key) return &k;
  return nullptr;
}

const ValueForm& numeric_form(const KeySpec& key) {
  for (const ValueForm& form : key.forms)
    if (form.type == ValueType::number || form.type == ValueType::integer) return form;
  throw std::logic_error("pipeline key '" + std::string(key.name) + "' is not a number");
}

const std::vector<KeyBlock>& pipeline_blocks() {
  static const std::vector<KeyBlock> blocks = make_blocks();
  return blocks;
}

const KeyBlock& pipeline_block(std::string_view name) {
  for (const KeyBlock& b : pipeline_blocks())
    if (b.name == name) return b;
  throw std::logic_error("no pipeline key block '" + std::string(name) + "'");
}

}  // namespace tw::detail
