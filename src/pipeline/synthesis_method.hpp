#pragma once
// One seam for every synthesis method (DESIGN.md, "Synthesis methods behind one seam";
// docs/methods.md). A method takes its domain (the classes or areas of the config it serves),
// plans their lines or placements once for the world, and says what the renderer needs of them:
// the windows of its items, how a tile renders them, what of them a tile's cache key covers and
// how its entry travels in a plan folder. plan_world, render_tile, the tile cache and the plan
// codec loop over the methods; none of them names one.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/content_hash.hpp"
#include "pipeline/method_plan.hpp"
#include "pipeline/plan.hpp"
#include "raster/sparse_raster.hpp"

namespace tw {

class OutputFolder;

namespace detail {
struct ExistingFeatures;
struct FeatureRibbons;
class InputCheck;
class PlanObjects;
}  // namespace detail

// When a method plans. Lines methods make the lines of their classes before the ribbons are cut
// (everything after treats them as read); placements methods synthesize on the ribbons, the
// terrain plan and the placements of the methods before them.
enum class MethodStage { lines, placements };

// What a method sees while planning; the pointers fill in as plan_world goes on.
struct MethodContext {
  const PipelineConfig& config;  // with the methods' defaults (resolve_defaults)
  const PlanOptions& options;
  const HeightfieldSource& source;
  const Heightfield& heightfield;  // the world's, without pixels
  // Per class (config order): the lines read; a lines method fills its classes'.
  std::vector<std::vector<LineFeature>>& lines;
  // The plan so far: grid, output window, report, and the entries of every method (those before
  // this one planned already, in plan.methods order).
  WorldPlan& plan;
  Warnings& warnings;
  const detail::ExistingFeatures* existing = nullptr;  // from conformance on
  const detail::FeatureRibbons* ribbons = nullptr;     // in the placements stage
  // What the methods reserve for themselves after their ingest (SynthesisMethod::reserved), in
  // method order: the lines methods keep out of them.
  std::vector<Polygon> reserved{};
};

// One tile's fact of a method (SynthesisMethod::tile_fact) and the tile it came from, as error
// messages name it ("tile", "tile 3").
struct MethodTileFact {
  std::string where;
  std::string fact;
};

// Where a method writes its run outputs (SynthesisMethod::write_outputs).
struct MethodOutputs {
  std::filesystem::path dir;  // the output folder
  OutputFolder& transaction;  // stages every file (the manifest hashes what it staged)
  RunReport& report;          // completed with what the outputs name (placements files)
  std::vector<MethodTileFact> tile_facts;  // its fact of every tile, in tile order
};

// What a method's synthesis tasks see (terraweave plan --synthesis tasks, synth-feature,
// complete-plan: pipeline/synthesis_job.hpp). The protocol (syntheses.json, its dependency
// graph and waves, the results' files, the completion's journal) is the pipeline's; what a task
// is, how it runs and how its results enter the plan are the method's.
struct MethodTasks {
  const PipelineConfig& config;  // with the methods' defaults (resolve_defaults)
  std::optional<std::string> backend;
  // The synthesis store: the cache when planning (none: nothing is reused), else syntheses.json's
  // `store`.
  std::optional<std::filesystem::path> store;
  std::filesystem::path plan_dir;
  Warnings& warnings;
};

// A task's stored result (SynthesisMethod::complete_tasks): its file, as messages name it, and
// its bytes.
struct MethodTaskResult {
  std::string file;
  std::string bytes;
};

// What a task run returns (SynthesisMethod::run_task): its result, which the pipeline stores
// under the task's key, and why it reused a stored synthesis instead of running (the cache's
// finer check: docs/cache.md), if it did.
struct MethodTaskRun {
  std::string result;
  std::optional<std::string> reused_why;
};

// What the ribbons stage (and the ingest's clip halo) needs of a line class from the methods that
// make its lines or synthesize on them (SynthesisMethod::ribbon_needs), so the stages read no
// method's options.
struct RibbonNeeds {
  std::optional<double> piece_length;     // metres; absent: the ribbons' default
  std::optional<double> synthesis_width;  // a synthesis ribbon of its own, metres
  bool counts_short_lines = false;  // lines shorter than a piece are counted, not warned about
};

class SynthesisMethod {
 public:
  virtual ~SynthesisMethod() = default;

  // Its entry's name in plan.json and the stage its planning is timed as (report.json).
  virtual std::string name() const = 0;
  virtual std::string stage_name() const { return name(); }
  virtual MethodStage stage() const = 0;
  // Whether the config gives it work (false: its entry stays empty and plan() is not called).
  virtual bool serves(const PipelineConfig& config, const PlanOptions& options) const = 0;
  // Whether it makes the lines of this class (a lines method): then the class reads no source,
  // and its report's source is class_source's.
  virtual bool makes_lines_of(const FeatureClassConfig& /*c*/) const { return false; }
  virtual std::string class_source(const FeatureClassConfig& /*c*/) const { return {}; }
  // What the ribbons need of the class from it (the patterns: their piece length and ribbon
  // width; grown: short lines counted); class_ribbon_needs gathers every method's.
  virtual RibbonNeeds ribbon_needs(const FeatureClassConfig& /*c*/) const { return {}; }
  // An empty entry: what a plan without its classes holds.
  virtual std::unique_ptr<MethodPayload> empty_payload() const = 0;

  // Before any stage reads the config: fills in the defaults of its options that come from its
  // inputs (the patterns: a class's synthesis width and delta from its exemplars), so that every
  // reader after it (the stages' options, the synthesis tasks and keys) sees them resolved.
  // Called for every method, in method order (with_method_defaults, below).
  virtual void resolve_defaults(PipelineConfig& /*config*/) const {}
  // Checks one of the config's inputs (PipelineConfig::inputs) before any stage starts, if it is
  // its own (the patterns: an exemplar image; grown: an element set); the file exists. Throws
  // tw::Error "<input.named_at>: ..." when it cannot be used; false: not its own (the pipeline
  // opens raster and vector data itself). `check` (detail/input_check.hpp) holds what the
  // checks share, the run cache among it.
  virtual bool check_input(const InputFile& /*input*/, detail::InputCheck& /*check*/) const {
    return false;
  }

  // Reads its own inputs with the plan's ingest (warnings in the ingest's order). Called for
  // every method, before conformance; context.existing is not there yet.
  virtual void ingest(MethodContext& /*context*/, MethodPlan& /*entry*/) const {}
  // After its ingest: the polygons it keeps for itself (the areas' polygons), which plan_world
  // gathers into context.reserved for the lines methods to keep out of.
  virtual std::vector<Polygon> reserved(const MethodContext& /*context*/,
                                        const MethodPlan& /*entry*/) const {
    return {};
  }
  // What `terraweave validate` checks of its inputs besides the plan's ingest (the areas:
  // their sketches), timed as the stage validate_stage() names ("": nothing to check).
  virtual std::string validate_stage() const { return {}; }
  virtual void validate(const PipelineConfig& /*config*/, Warnings& /*warnings*/) const {}
  // Plans its domain: the lines of its classes into context.lines (lines stage), or its
  // placements into the entry; its part of the report into context.plan.report (its own type,
  // method_report<T>).
  virtual void plan(MethodContext& context, MethodPlan& entry) const = 0;
  // While the placements methods after it plan (before collect): what they keep out of, burnt
  // into `forbidden` over `lattice` (the patterns: their opaque coverage on the ground, which
  // the areas' shapes avoid). Through this hook a method reads another's work without its
  // types (docs/methods.md).
  virtual void keep_out(const MethodPlan& /*entry*/, const GridSpec& /*lattice*/,
                        SparseRaster<std::uint8_t>& /*forbidden*/) const {}
  // After every method planned, in method order: the entry as the renderer needs it (splat
  // materials into plan.splat_materials, in order of first use).
  virtual void collect(MethodContext& /*context*/, MethodPlan& /*entry*/) const {}

  // The output pixels each of its items can touch (index_plan bins them into entry.index).
  virtual std::vector<Window> windows(const WorldPlan& /*plan*/,
                                      const MethodPlan& /*entry*/) const {
    return {};
  }
  // Whether it writes into a tile's layers: then render() is called for every tile and its item
  // hashes enter the tile's cache key (a section named after the method).
  virtual bool renders() const { return false; }
  // Adds its items meeting `window` (entry.index) into the window's height and splat.
  virtual void render(const WorldPlan& /*plan*/, const MethodPlan& /*entry*/,
                      const Window& /*window*/, Raster<float>& /*height*/,
                      SplatLayers& /*splat*/) const {}
  // Per item (entry.index order): the hash of everything render() reads of it.
  virtual std::vector<ContentHash> item_hashes(const WorldPlan& /*plan*/,
                                               const MethodPlan& /*entry*/) const {
    return {};
  }

  // A fact of every rendered tile that its outputs need (the areas: the final height under each
  // instance), from the tile's height layer over `halo`, for the pixels of `core`; kept with
  // the tile in the tile cache and in a worker's tile result under tile_fact_key() ("": none).
  virtual std::string tile_fact_key() const { return {}; }
  virtual std::string tile_fact(const WorldPlan& /*plan*/, const MethodPlan& /*entry*/,
                                const Raster<float>& /*height*/, const Window& /*halo*/,
                                const Window& /*core*/) const {
    return {};
  }
  // Its run outputs beside the layers (placements/, areas.gpkg, ornaments.gpkg), timed as the
  // stage outputs_stage() names; "" when the plan gives it none to write.
  virtual std::string outputs_stage(const WorldPlan& /*plan*/, const MethodPlan& /*entry*/) const {
    return {};
  }
  virtual void write_outputs(const WorldPlan& /*plan*/, const MethodPlan& /*entry*/,
                             MethodOutputs& /*outputs*/) const {}

  // Writes its part of the run's report (RunReport::method_parts, method_report<T>) into its
  // places in report.json `json`: the built-in methods into the classes, their features and
  // top-level keys; another method under `methods.<name>`. Called for every method, in method
  // order, once the rest is there: the one way a method's report reaches report.json.
  virtual void report_json(const RunReport& /*report*/, const PipelineConfig& /*config*/,
                           nlohmann::json& /*json*/) const {}
  // Its part of the run's report (RunReport::method_parts: what plan() put there, of its own
  // type) in the plan folder (objects through `objects`), and back. What changes from one run of
  // the same inputs to the next stays outside the plan's hash: take_report_timings moves it out
  // of the part (null: nothing), restore_report_timings puts it back.
  virtual nlohmann::json encode_report(const MethodPayload& part,
                                       detail::PlanObjects& objects) const;
  virtual std::unique_ptr<MethodPayload> decode_report(const nlohmann::json& value,
                                                       detail::PlanObjects& objects) const;
  virtual nlohmann::json take_report_timings(MethodPayload& part) const;
  virtual void restore_report_timings(const nlohmann::json& /*timings*/,
                                      MethodPayload& /*part*/) const {}

  // Whether its placements can be made as synthesis tasks apart from the plan (then the
  // placements methods after it plan in complete-plan, after every task).
  virtual bool makes_tasks() const { return false; }
  // The tasks its entry splits into, for syntheses.json's `features`: one object per synthesis,
  // in synthesis order, with at least `index`, `name`, `key`, `after` (the earlier ones it
  // waits for), `task` (false: reused from the store) and `wave`.
  virtual nlohmann::json plan_tasks(const WorldPlan& plan, MethodTasks& tasks) const;
  // Runs the task at `index` of `list` (syntheses.json) on the stored plan.
  virtual MethodTaskRun run_task(const WorldPlan& plan, MethodTasks& tasks,
                                 const nlohmann::json& list, std::size_t index) const;
  // Puts every synthesis of `list` into its entry (`result(i)`: the stored result of task i;
  // it throws when the task has not run),
  // as plan() would have; returns the tasks' own seconds, summed.
  virtual double complete_tasks(WorldPlan& plan, MethodPlan& entry, MethodTasks& tasks,
                                const nlohmann::json& list,
                                const std::function<MethodTaskResult(std::size_t)>& result) const;

  // Its entry in plan.json (objects through `objects`), and back.
  virtual nlohmann::json encode(const MethodPlan& entry, detail::PlanObjects& objects) const = 0;
  virtual void decode(const nlohmann::json& value, detail::PlanObjects& objects,
                      MethodPlan& entry) const = 0;
};

// The built-in methods in plan order, which the outputs' bytes depend on: the lines methods
// first (grown ornaments, then networks), then Zhou's DP along ribbons (patterns), then the
// shape-patterns in areas, which avoid the patterns.
const std::vector<const SynthesisMethod*>& builtin_synthesis_methods();

// `methods`, or the built-in ones when it is empty.
const std::vector<const SynthesisMethod*>& methods_or_builtin(
    const std::vector<const SynthesisMethod*>& methods);

// The config with every method's defaults resolved (SynthesisMethod::resolve_defaults), in the
// methods' order (empty: the built-in ones): what plan_world and the synthesis tasks read.
PipelineConfig with_method_defaults(PipelineConfig config,
                                    const std::vector<const SynthesisMethod*>& methods = {});

// A class's ribbon needs from every method, in the methods' order (empty: the built-in ones): the
// last one giving a value wins; short lines are counted when any method counts them.
RibbonNeeds class_ribbon_needs(const FeatureClassConfig& c,
                               const std::vector<const SynthesisMethod*>& methods = {});

// Whether one of the methods (empty: the built-in ones) makes the class's lines.
bool lines_made_by_a_method(const FeatureClassConfig& c,
                            const std::vector<const SynthesisMethod*>& methods = {});

// The entry of the method named `name` in the plan; null when the plan has none.
const MethodPlan* find_method_plan(const WorldPlan& plan, const std::string& name);
MethodPlan* find_method_plan(WorldPlan& plan, const std::string& name);

}  // namespace tw
