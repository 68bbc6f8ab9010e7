#include "pipeline/detail/pipeline_keys.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/key_forms.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "terrain/features.hpp"

namespace tw::detail {

namespace {

using namespace key_forms;

const std::vector<std::string_view> kEngines{"unreal", "unity", "godot", "terrain3d"};

std::vector<KeyBlock> table_blocks() {
  const RoadProfile road;
  const RiverProfile river;
  const RidgeProfile ridge;
  const LineRepair repair;
  const GenerateConfig generate;
  const OutputConfig output;
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
           {"repair", {block("repair")}, "this class's repair, over the pipeline's"},
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
      {"lead",
       "A fixed direction (an area class's or a network's `lead`).",
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

KeyBlock& block_named(std::vector<KeyBlock>& blocks, std::string_view name) {
  for (KeyBlock& b : blocks)
    if (b.name == name) return b;
  throw std::logic_error("no pipeline key block '" + std::string(name) + "'");
}

// The table's own blocks with the methods' keys and blocks in their places: each key after the
// one it names, the methods' blocks before `existing`, in the methods' order.
std::vector<KeyBlock> make_blocks() {
  std::vector<KeyBlock> blocks = table_blocks();
  std::vector<KeyBlock> methods_blocks;
  for (const MethodKeys& method : builtin_method_keys()) {
    for (const PlacedKey& placed : method.keys) {
      std::vector<KeySpec>& keys = block_named(blocks, placed.block).keys;
      const auto after = std::find_if(keys.begin(), keys.end(),
                                      [&](const KeySpec& k) { return k.name == placed.after; });
      if (after == keys.end())
        throw std::logic_error("pipeline key '" + std::string(placed.key.name) + "' follows '" +
                               std::string(placed.after) + "', which " + std::string(placed.block) +
                               " lacks");
      keys.insert(std::next(after), placed.key);
    }
    methods_blocks.insert(methods_blocks.end(), method.blocks.begin(), method.blocks.end());
  }
  const auto existing = std::find_if(blocks.begin(), blocks.end(),
                                     [](const KeyBlock& b) { return b.name == "existing"; });
  blocks.insert(existing, methods_blocks.begin(), methods_blocks.end());
  return blocks;
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
