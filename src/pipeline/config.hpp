#pragma once
// A pipeline file (YAML, docs/pipeline.md) parsed into plain values. Every relative path is
// already resolved: against the pipeline file's folder, or against the current folder for
// values given with --set. Lengths are metres.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <string>
#include <string_view>
#include <vector>

#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "layers/export.hpp"
#include "layers/write.hpp"
#include "pipeline/grow_config.hpp"
#include "pipeline/method_options.hpp"
#include "pipeline/network_config.hpp"
#include "synth/feature_synthesis.hpp"
#include "terrain/features.hpp"

namespace tw {

// A seeded synthetic heightfield, used when the pipeline names no heightfield file.
struct GenerateConfig {
  int width = 1024;                // cells
  int height = 1024;               // cells
  double pixel_size = 4.0;         // metres
  double relief = 120.0;           // metres between lowest and highest point (roughly)
  std::string crs = "EPSG:32631";  // a metric CRS
  double origin_x = 500000.0;      // world x of the west edge
  double origin_y = 5000000.0;     // world y of the north edge
};

// Curvilinear pattern synthesis (Zhou et al. 2013) along a feature class (issue #4).
// Where one exemplar channel goes: "height" (metres added to the terrain) or "splat.<material>"
// (a splat weight: the pattern's coverage times the channel, taken from the other materials).
struct ChannelMapping {
  std::string channel;  // exemplar channel name: A (alias alpha), R, G, B, height, ...
  std::string target;   // "height" or "splat.<material>"
};

// An OSM-style tag selection (docs/osm.md): features whose column `key` holds one of
// `values`. Several selections must all match; they are ANDed with `where`.
struct TagSelection {
  std::string key;
  std::vector<std::string> values;
};

// One `bind` rule of a mix (choose: mix): the pieces it selects use only exemplar `exemplar`
// (an index into SynthesisConfig::exemplars). It selects the lines its `where` / `tags` match
// (evaluated by OGR on the class's layer, both empty: every line) and, with near_junction > 0,
// only their pieces within that many metres of a junction (synth/exemplar_mix.hpp PieceBinding).
struct ExemplarBinding {
  std::size_t exemplar = 0;
  std::string where;
  std::vector<TagSelection> tags;
  double near_junction = 0.0;
  std::string key;  // "features.roads.synthesis.bind.0", for messages
};

// The patterns method's name (SynthesisMethod::name()): a line class's `synthesis:` block is its
// options, method_options<SynthesisConfig>(feature_class, kPatternsMethodName).
inline constexpr const char* kPatternsMethodName = "patterns";

struct SynthesisConfig : MethodOptionsOf<SynthesisConfig> {
  // One or more; NAME_height.tif beside NAME.png, when present, is read as channel "height".
  std::vector<std::filesystem::path> exemplars;
  ExemplarChoice choice = ExemplarChoice::by_seed;
  // choose: mix only. Colour units added to every seam between pieces of different exemplars
  // (SynthParams::switch_cost), and the rules binding stretches to exemplars, first match wins.
  int switch_cost = 0;
  std::vector<ExemplarBinding> bind;
  // Piece length, metres; absent: from the exemplar (the patterns method's resolve_defaults).
  std::optional<double> delta;
  double scale = 8.0;  // exemplar texels per metre of ribbon
  // Ribbon width of the synthesis in metres (s * width texels of the exemplar span it); absent:
  // from the exemplar (the patterns method's resolve_defaults); `width: feature`: each feature's
  // width (attribute or the class's `width`).
  std::optional<double> width;
  bool width_of_feature = false;
  // Set by the patterns method's resolve_defaults where width / delta were derived from the
  // exemplar.
  bool width_from_exemplar = false, delta_from_exemplar = false;
  bool stitch = true;
  // A piece with no valid position (a junction disc, an earlier pattern) stays empty; false:
  // such a piece is an error naming the feature and the piece.
  bool empty_pieces = true;
  // The fraction of each piece that must be opaque at a valid position (SynthParams); absent:
  // from the exemplar (a tenth of its natural coverage).
  std::optional<double> min_coverage;
  Objective objective = Objective::pattern;  // `objective: pattern | paper`
  double coverage_weight = 2.0;              // the pattern objective's weight against gamma
  // Costs with alpha as a fraction (the paper's option for soft-edged exemplars) instead of
  // opaque / transparent at alpha 0.5.
  bool continuous_alpha = false;
  // Metres either side of each seam over which the pattern's channels (not its coverage)
  // blend into the next piece's (render_pattern); 0 = exact copies.
  double feather = 0.0;
  std::uint64_t seed = 0;
  std::string backend;         // "" = the pipeline's backend
  double height_detail = 1.0;  // factor on the metres of the exemplar's channels mapped to height
  // Empty = the default mapping: A -> splat.<class>_pattern, height -> height (when present).
  std::vector<ChannelMapping> channels;
};

// The OGR SQL attribute filter of `tags` and `where` together ("" when both are empty).
std::string selection_where(const std::vector<TagSelection>& tags, const std::string& where);

struct FeatureClassConfig {
  std::string name;  // the key under `features`, e.g. "roads"
  std::filesystem::path source;
  std::string layer;  // "" = the source's only layer
  std::string where;  // OGR attribute filter, "" = every feature
  // With tags, `kind` defaults from their key and widths come from the OSM tag table.
  std::vector<TagSelection> tags;
  FeatureKind kind = FeatureKind::road;
  std::string width_attribute;  // "" = every feature has `width`
  // Metres, > 0 (fallback when the attribute is missing or null); 0 = none (with tags only).
  double width = 0.0;
  // The profile of `kind` (the others keep their defaults), from the `profile` key.
  RoadProfile road;
  RiverProfile river;
  RidgeProfile ridge;
  // `conform.corridor`: metres either side of each line within which it moves onto the DEM's
  // valley floor (rivers) or crest (ridges) before anything is built on it; 0 = as drawn.
  double conform_corridor = 0.0;
  LineRepair repair;  // the pipeline's `repair`, overridden key by key by the class's own
  // The blocks of the class that methods own, in the order their readers made them: the
  // patterns' `synthesis:` (SynthesisConfig), the grown ornaments' `grow:` (GrowConfig, also
  // for `kind: hedge | wall | trail | ditch`) and the networks' `network:` (NetworkClassConfig);
  // method_options finds one.
  std::vector<MethodConfigPart> methods;
};

// The options of method `method` in line class `feature_class` as its own type T (the class's
// `synthesis:` block: method_options<SynthesisConfig>(c, kPatternsMethodName)); null: none.
template <class T>
const T* method_options(const FeatureClassConfig& feature_class, const std::string& method) {
  return find_method_options<T>(feature_class.methods, method);
}

// The same, added (default T) when missing: a method's reader fills its block with it.
template <class T>
T& method_options(FeatureClassConfig& feature_class, const std::string& method) {
  return method_options_in<T>(feature_class.methods, method);
}

// Whether line class `feature_class` has a block of method `method`.
inline bool has_method_options(const FeatureClassConfig& feature_class, const std::string& method) {
  for (const MethodConfigPart& part : feature_class.methods)
    if (part.method == method) return true;
  return false;
}

// Avoidance input: polygons are burnt as they are, lines are buffered by `width`.
struct ExistingConfig {
  std::filesystem::path source;
  std::string layer;
  std::string where;
  std::vector<TagSelection> tags;  // ANDed with where
  double width = 0.0;              // metres, required (> 0) when the layer holds lines
};

// `output.tiles` (docs/tiles.md): the output grid rendered and written in square tiles of
// `size` pixels, each file holding `overlap` more pixels on every side (clamped to the grid).
struct TilesConfig {
  int size = 0;  // 0: untiled (one file per layer)
  int overlap = 0;
};

// The largest tile side and overlap, pixels (a tile's layers stay well under a few GiB).
inline constexpr int kMaxTileSize = 16384;
inline constexpr int kMaxTileOverlap = 4096;

struct OutputConfig {
  std::filesystem::path dir = "out";
  // `formats` (or the older `exr` / `geotiff` booleans): which encodings of every layer to
  // write; at least one.
  bool exr = true;
  bool geotiff = true;
  bool preview = true;
  // `exr_half`: true = every EXR channel half, false = every one float32, absent = automatic
  // (splat weights half, the rest float32).
  ExrPixels exr_pixels = ExrPixels::automatic;
  // `exr_compression`: automatic (per layer, docs/performance.md) or one OpenEXR codec.
  ExrCompression exr_compression = ExrCompression::automatic;
  // `compress`, `predictor`, `cog`, `overviews` (docs/pipeline.md); metadata is the run's.
  GeoTiffOptions tiff;
  // `crs`: the CRS of every output ("" = a projected heightfield's own, a geographic one's UTM
  // zone); anything PROJ reads (EPSG:2169, a WKT, a PROJ string) or "utm" (the zone of the
  // heightfield's centre).
  std::string crs;
  TilesConfig tiles;
};

// `avoidance` (docs/tiles.md): the avoidance layer's distance band is capped at max_distance
// metres, so a tile needs only that much halo to be exact.
struct AvoidanceConfig {
  double max_distance = 500.0;
};

// A region of interest: the output grid covers only this rectangle, in metres of the
// heightfield's CRS (its local metric frame when the source is geographic). Features are still
// read, and patterns synthesized, over the whole heightfield, so a close-up shows the same
// placements as the full run; only the terrain and the layers are limited to the region.
struct RegionConfig {
  double min_x = 0.0;
  double min_y = 0.0;
  double max_x = 0.0;
  double max_y = 0.0;
};

// A file read beside an input where it exists (an exemplar's NAME_height.tif twin), and what it
// is in report.json's manifest (`inputs[].role`).
struct CompanionFile {
  std::filesystem::path path;
  std::string role;
};

// A file a run opens, and where the pipeline names it, so that a missing or unreadable one is
// reported at its key (check_inputs). Raster and vector data the pipeline opens itself; a
// method's own file (Kind::method) the method that reads it checks, which knows it by its role
// (SynthesisMethod::check_input).
struct InputFile {
  enum class Kind { raster, vector, method };
  std::filesystem::path path;
  Kind kind = Kind::raster;
  std::string named_at;  // "file:line:col: key.path" or "--set key=value: key.path"
  // A method's input: what it is, set by the method's reader and written as its role in the
  // manifest (the patterns' "exemplar", grown's "element_set"). Raster and vector data are the
  // "heightfield" and "vector" there.
  std::string role{};
  std::vector<CompanionFile> companions{};  // in the manifest after it, those that exist
};

// One `--set key.path=value` (value parsed as a YAML scalar or flow collection).
struct Override {
  std::string key_path;
  std::string value;
};

struct PipelineConfig {
  std::filesystem::path file;  // the pipeline file itself ("" when parsed from text)
  int version = 1;
  std::uint64_t seed = 0;
  std::optional<std::filesystem::path> heightfield;  // absent -> generate
  GenerateConfig generate;
  std::optional<double> resolution;    // output cell size in metres; absent = the heightfield's
  std::optional<RegionConfig> region;  // absent = the whole heightfield
  // How the heightfield is read between its cells when resampled to `resolution` or a region.
  Resampling resampling = Resampling::bilinear;
  OutputConfig output;
  std::string backend = "auto";              // cpu | opencl | auto
  std::vector<FeatureClassConfig> features;  // in precedence order: later wins on overlaps
  // The methods' own options, in the order their readers made them (the `kind: area` classes
  // are the areas method's, `synthesis_order` the patterns'); method_options finds one.
  std::vector<MethodConfigPart> methods;
  std::vector<ExistingConfig> existing;
  AvoidanceConfig avoidance;
  // Synthesis canvas cell size in metres, independent of `resolution` (placements never
  // depend on the output grid).
  double synthesis_resolution = 1.0;
  // `cache`: the folder where runs keep and reuse syntheses and tiles (docs/cache.md); --cache
  // replaces it. Absent: no cache.
  std::optional<std::filesystem::path> cache_dir;
  // Any warning fails the run before anything is written (also `--strict`).
  bool strict = false;
  LineRepair repair;  // `repair`: how messy lines are cleaned (each class may override)
  // `export`: engine exports written under <output.dir>/export/<engine>/ (docs/exports.md).
  std::vector<EngineExportOptions> exports;
  std::vector<InputFile> inputs;  // every file named, in the order of the keys read
  // The manifest's view of the configuration: the --set values applied, in order, and the
  // whole tree after --vars and --set, as JSON text (report.json `overrides`, `config`).
  std::vector<Override> overrides;
  std::string resolved_json;
};

// The options of method `method` in `config` as its own type T; null when the config has none
// (or, for a method that names another's type, of another type).
template <class T>
const T* method_options(const PipelineConfig& config, const std::string& method) {
  return find_method_options<T>(config.methods, method);
}

// The same, added (default T) when missing: a method's reader fills its options with it.
template <class T>
T& method_options(PipelineConfig& config, const std::string& method) {
  return method_options_in<T>(config.methods, method);
}

// The patterns' config-level option (`synthesis_order`), in PipelineConfig::methods under
// kPatternsMethodName: the classes with synthesis in the order they are synthesized, each
// avoiding the patterns of the classes before it (default: precedence order).
struct SynthesisOrder : MethodOptionsOf<SynthesisOrder> {
  std::vector<std::string> classes;
};

// The classes with synthesis in synthesis order; empty when the config has none.
inline const std::vector<std::string>& synthesis_order(const PipelineConfig& config) {
  static const std::vector<std::string> none;
  const SynthesisOrder* order = method_options<SynthesisOrder>(config, kPatternsMethodName);
  return order ? order->classes : none;
}

// A variables file (`--vars FILE`, docs/pipeline.md): a YAML mapping of name: value. Every
// `${name}` in a value of the pipeline file is replaced by its value, before the overrides.
struct Variables {
  std::string file;  // "" = none given
  std::map<std::string, std::string> values;
};

// Throws tw::Error naming the file (and line) when it is not a mapping of names to scalars.
Variables load_variables(const std::filesystem::path& file);

// Splits "key.path=value"; throws tw::Error when there is no '=' or the key is empty.
Override parse_override(std::string_view assignment);

// The largest pipeline file read (16 MiB).
inline constexpr std::uintmax_t kMaxPipelineFileBytes = std::uintmax_t(16) << 20;

// Reads and validates a pipeline file, applying `overrides` first. Throws tw::Error with
// "file:line:col: key.path: problem" (or "--set key.path=value: ...") on any problem, and
// for a path that is not a regular file or is over kMaxPipelineFileBytes. Every mapping must
// hold each key once, and the file one YAML document.
PipelineConfig load_pipeline(const std::filesystem::path& file,
                             const std::vector<Override>& overrides = {},
                             const Variables& variables = {});
// The same from text; relative paths resolve against `base_dir`, messages name `file_label`.
PipelineConfig parse_pipeline(std::string_view yaml_text, const std::string& file_label,
                              const std::filesystem::path& base_dir,
                              const std::vector<Override>& overrides = {},
                              const Variables& variables = {});

// Throws tw::Error naming the key (heightfield, features.<class>.source, ...) of the first input
// path that reaches the network (geo/input_guard.hpp), unless `allow_network`.
void check_input_paths(const PipelineConfig& config, bool allow_network);

}  // namespace tw
