// terraweave's command line: a thin parse over library calls (pipeline/, synth/).
// Every tw::Error becomes one line "terraweave: error: <message>" (newlines escaped) and exit
// code 1; usage errors are one line "terraweave: usage error: ..." and exit with 2.
#include <cpl_error.h>
#include <fmt/format.h>
#include <gdal.h>
#include <CLI/CLI.hpp>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdint>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "commands/area_command.hpp"
#include "commands/grow_command.hpp"
#include "commands/network_command.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

#include "cli/gdal_loader.hpp"
#include "cli/view_server.hpp"
#include "commands/big_world.hpp"
#include "commands/diff.hpp"
#include "commands/exemplar_command.hpp"
#include "commands/export_command.hpp"
#include "commands/synth_command.hpp"
#include "commands/view.hpp"
#include "pipeline/config.hpp"
#include "pipeline/job.hpp"
#include "pipeline/run.hpp"
#include "pipeline/schema.hpp"
#include "pipeline/synthesis_job.hpp"
#include "pipeline/version.hpp"

namespace {

// GDAL's own messages go to the log at debug level: our errors already name the culprit, and
// a failing command must print one line, not GDAL's and ours.
void log_gdal_message(CPLErr level, CPLErrorNum number, const char* message) {
  tw::logger().debug("GDAL {} ({}): {}", int(level), number, message ? message : "");
}

struct PipelineArgs {
  std::string file;
  std::vector<std::string> overrides;
  std::string variables;              // --vars FILE ("" = none)
  std::optional<std::uint64_t> seed;  // --seed N: the same as a last --set seed=N
};

void add_pipeline_args(CLI::App& command, PipelineArgs& args) {
  command.add_option("PIPELINE", args.file, "pipeline file (YAML, see docs/pipeline.md)")
      ->required();
  command.add_option("--set", args.overrides,
                     "override a value of the pipeline file: key.path=value (repeatable)");
  command.add_option("--vars", args.variables,
                     "variables file (YAML name: value) for ${name} in the pipeline's values");
  command.add_option("--seed", args.seed, "the run's seed (the same as --set seed=N)");
}

tw::PipelineConfig load(const PipelineArgs& args) {
  std::vector<tw::Override> overrides;
  for (const std::string& o : args.overrides) overrides.push_back(tw::parse_override(o));
  if (args.seed) overrides.push_back({"seed", std::to_string(*args.seed)});
  const tw::Variables variables =
      args.variables.empty() ? tw::Variables{} : tw::load_variables(args.variables);
  return tw::load_pipeline(args.file, overrides, variables);
}

int run_command(const PipelineArgs& args, const tw::RunOptions& options) {
  const tw::RunReport report = tw::run_pipeline(load(args), options);
  for (const auto& stage : report.stages)
    std::printf("%-16s %8.3f s\n", stage.stage.c_str(), stage.seconds);
  if (!report.warnings.empty()) std::printf("%-16s %8zu\n", "warnings", report.warnings.size());
  std::printf("%-16s %8.3f s, %zu files in %s\n", "total", report.total_seconds,
              report.outputs.size(),
              report.outputs.empty()
                  ? "-"
                  : tw::single_line(report.outputs.front().parent_path().string()).c_str());
  return 0;
}

int validate_command(const PipelineArgs& args, const tw::RunOptions& global) {
  tw::RunOptions options = global;
  options.write_outputs = false;
  const tw::RunReport report = tw::run_pipeline(load(args), options);
  std::size_t features = 0;
  for (const auto& c : report.classes) features += c.features.size();
  std::printf("%s: ok (%zu feature classes, %zu features, grid %d x %d, %zu warnings)\n",
              tw::single_line(args.file).c_str(), report.classes.size(), features,
              report.grid.width, report.grid.height, report.warnings.size());
  return 0;
}

// Exit 0 when the runs are the same, 1 when they differ (as diff(1); 2 on trouble).
int diff_command(const std::string& a, const std::string& b, bool verify) {
  const tw::RunDifference difference = tw::diff_runs(a, b, verify);
  for (const std::string& line : tw::describe(difference))
    std::printf("%s\n", tw::single_line(line).c_str());
  return difference.identical() ? 0 : 1;
}

// Writes the page; with --serve, serves its folder (and, with --exemplar, the drawing page) on
// 127.0.0.1 until stopped.
int view_command(const tw::ViewOptions& options, bool serve, tw::ViewServeOptions serve_options) {
  const std::filesystem::path page = tw::write_view(options);
  std::printf("%s\n", tw::single_line(page.string()).c_str());
  if (!serve) return 0;
  serve_options.page = page;
  tw::serve_view(options, serve_options);
  return 0;
}

int plan_command(const PipelineArgs& args, tw::PlanJobOptions options) {
  // What the tasks read the pipeline with again (job.json): --seed and --vars were lost there,
  // so render-tile drew another world or failed on ${name} (issue #24 item 2).
  options.overrides = args.overrides;
  if (args.seed) options.overrides.push_back("seed=" + std::to_string(*args.seed));
  options.variables = args.variables;
  const tw::PipelineConfig config = load(args);
  if (options.output_dir.empty()) options.output_dir = config.output.dir;
  const tw::PlannedJob job = tw::plan_job(config, options);
  std::printf("plan %s: %zu tiles, %zu syntheses to run, %zu warnings, in %s\n", job.plan.c_str(),
              job.tiles, job.syntheses, job.warnings,
              tw::single_line(job.plan_dir.string()).c_str());
  return 0;
}

int synth_feature_command(const std::string& plan, int feature) {
  const tw::SynthesisJobResult result =
      tw::synthesize_job_feature(tw::find_plan_dir(plan), feature);
  const std::string what =
      result.synthesized ? "synthesized" : "reused from the cache (" + result.why + ")";
  std::printf("feature %d (%s): %s in %.3f s\n", result.feature,
              tw::single_line(result.name).c_str(), tw::single_line(what).c_str(), result.seconds);
  return 0;
}

int complete_plan_command(const std::string& plan, bool strict) {
  const tw::PlannedJob job = tw::complete_job_plan(tw::find_plan_dir(plan), strict);
  std::printf("plan %s: %zu tiles, %zu warnings, in %s\n", job.plan.c_str(), job.tiles,
              job.warnings, tw::single_line(job.plan_dir.string()).c_str());
  return 0;
}

// The end of a one-shot command whose files are closed and renamed: stdout and stderr flushed
// (a failed flush is exit code 1), then _Exit, skipping the static destructors and the joins of
// OpenEXR's and TBB's idle worker threads (a render-tile's last milliseconds of wall time on a
// loaded machine, docs/performance.md). Not for a command that may leave work to destructors.
[[noreturn]] void exit_after_files_committed(int code) {
  if (std::fflush(nullptr) != 0 && code == 0) code = 1;
  std::_Exit(code);
}

int render_tile_command(const std::string& plan, int tile) {
  const tw::TileJobResult result = tw::render_job_tile(tw::find_plan_dir(plan), tile);
  std::printf("tile %d: %zu files in %.3f s\n", result.tile, result.files.size(), result.seconds);
  // render_job_tile returned: its files are renamed into place and its result written last.
  exit_after_files_committed(0);
}

int finish_command(const std::string& plan) {
  const tw::RunReport report = tw::finish_job(tw::find_plan_dir(plan));
  std::printf("%zu files in %s\n", report.outputs.size(),
              report.outputs.empty()
                  ? "-"
                  : tw::single_line(report.outputs.front().parent_path().string()).c_str());
  return 0;
}

// `terraweave run --help` shows the run's own options; the global ones (accepted before or
// after the subcommand) are listed in every subcommand's footer, read from the app itself so
// the two lists cannot disagree.
void list_global_options_in_subcommand_help(CLI::App& app) {
  std::string footer = "Global options (before or after the subcommand):";
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_name().empty() || option->get_name() == "--help") continue;
    footer +=
        fmt::format("\n  {:<18} {}", option->get_name(false, true), option->get_description());
  }
  for (CLI::App* sub : app.get_subcommands({})) sub->footer(footer);
}

// CLI11's PositiveNumber and NonNegativeNumber let NaN through and print their upper bound,
// DBL_MAX, in 309 digits: these say what is wrong in a few words.
CLI::Validator number_above(double bound, bool or_equal) {
  return CLI::Validator(
      [bound, or_equal](std::string& value) {
        char* end = nullptr;
        const double x = std::strtod(value.c_str(), &end);
        if (end == value.c_str() || *end != '\0') return "'" + value + "' is not a number";
        if (!std::isfinite(x)) return "'" + value + "' is not a finite number";
        if (or_equal ? x >= bound : x > bound) return std::string();
        return fmt::format("'{}' must be {} {:g}", value, or_equal ? ">=" : ">", bound);
      },
      or_equal ? "NONNEGATIVE" : "POSITIVE");
}

// NaN and infinities pass CLI11's ranges (every comparison with NaN is false), and then run for
// minutes or place nothing: every number option (CLI11's FLOAT, of every subcommand) is refused
// unless finite, here once so that a new option cannot forget it.
void refuse_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& value) {
        char* end = nullptr;
        const double x = std::strtod(value.c_str(), &end);
        return std::isfinite(x) ? std::string() : "'" + value + "' is not a finite number";
      },
      "");
  // Nested subcommands too (`network synthesize`).
  std::vector<CLI::App*> apps{&app};
  for (std::size_t i = 0; i < apps.size(); ++i)
    for (CLI::App* sub : apps[i]->get_subcommands({})) apps.push_back(sub);
  // An empty value ('') was the option's default, silently; 99999999999999999999 became
  // 2^64 - 1 for an unsigned option (CLI11 does not check strtoull's range).
  const CLI::Validator non_empty_value(
      [](std::string& value) { return value.empty() ? std::string("an empty value") : ""; }, "");
  const CLI::Validator unsigned_range(
      [](std::string& value) {
        std::uint64_t x = 0;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), x);
        return error == std::errc::result_out_of_range
                   ? "'" + value + "' is out of range (at most 18446744073709551615)"
                   : std::string();
      },
      "");
  for (CLI::App* a : apps)
    for (CLI::Option* option : a->get_options()) {
      if (option->get_type_name().find("FLOAT") != std::string::npos) option->check(finite);
      if (option->get_type_name().find("UINT") != std::string::npos) option->check(unsigned_range);
      if (option->get_items_expected_max() > 0 && !option->get_positional())
        option->check(non_empty_value);
    }
}

// TERRAWEAVE_FORK_BATCH=FILE (for tests/pipeline/bad_input_corpus_test.cpp): each line of FILE,
// "DIR<tab>STDOUT<tab>STDERR<tab>ARG<tab>ARG...", runs as `terraweave ARG...` in DIR, in a child
// forked from this process (loading the program's 265 libraries costs 0.2 s of CPU; a fork a
// millisecond), and its wait status is written to FILE.status, one a line. Each child is the
// program on its own: its exit code and signals are its own; one running past 60 s gets SIGALRM
// (TERRAWEAVE_FORK_BATCH_SECONDS: another limit, for sanitized builds, which run 2-5x slower).
unsigned fork_batch_seconds() {
  const char* text = std::getenv("TERRAWEAVE_FORK_BATCH_SECONDS");
  const long seconds = text != nullptr ? std::strtol(text, nullptr, 10) : 0;
  return seconds > 0 ? unsigned(seconds) : 60u;
}

int run_fork_batch(const char* file, int (*cli)(int, char**)) {
  std::FILE* in = std::fopen(file, "r");
  std::FILE* status = std::fopen((std::string(file) + ".status").c_str(), "w");
  if (in == nullptr || status == nullptr) return 2;
  // The drivers registered once here, not again in every child (no thread is started).
  GDALAllRegister();
  std::string line;
  for (int ch = std::fgetc(in); ch != EOF; ch = std::fgetc(in)) {
    if (ch != '\n') {
      line += char(ch);
      continue;
    }
    std::vector<std::string> fields(1);
    for (const char c : line) {
      if (c == '\t')
        fields.emplace_back();
      else
        fields.back().push_back(c);
    }
    fields.pop_back();  // every field ends with a tab
    line.clear();
    int wait_status = -1;
    std::fflush(nullptr);
    const pid_t pid = fields.size() >= 3 ? fork() : -1;
    if (pid == 0) {
      if (chdir(fields[0].c_str()) != 0 || !std::freopen(fields[1].c_str(), "w", stdout) ||
          !std::freopen(fields[2].c_str(), "w", stderr) || !std::freopen("/dev/null", "r", stdin))
        _exit(125);
      alarm(fork_batch_seconds());
      std::vector<char*> args{const_cast<char*>("terraweave")};
      for (std::size_t i = 3; i < fields.size(); ++i) args.push_back(fields[i].data());
      args.push_back(nullptr);
      const int code = cli(int(args.size()) - 1, args.data());
      // _exit: a library's exit handler (log4cplus, through GDAL) waits for a thread that only
      // the parent has.
      std::fflush(nullptr);
      _exit(code);
    }
    if (pid > 0 && waitpid(pid, &wait_status, 0) != pid) wait_status = -1;
    std::fprintf(status, "%d\n", wait_status);
  }
  std::fclose(in);
  return std::fclose(status) == 0 ? 0 : 2;
}

int cli_main(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
  if (const char* batch = std::getenv("TERRAWEAVE_FORK_BATCH"))
    return run_fork_batch(batch, cli_main);
  return cli_main(argc, argv);
}

namespace {

int cli_main(int argc, char** argv) {
  tw::set_gdal_error_handler(log_gdal_message);
  CLI::App app{"terraweave: terrain features for procedural worlds"};
  app.require_subcommand(1);
  app.set_version_flag("--version", tw::version_line());
  // Global options go before or after the subcommand: a subcommand passes what it does not
  // know to the app (fallthrough).
  app.fallthrough();
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "debug logging");
  app.add_flag("-q,--quiet", quiet, "warnings and errors only");
  tw::RunOptions run_options;
  app.add_option("--threads", run_options.threads, "worker threads (default: every core)")
      ->check(CLI::Range(1, tw::kMaxThreads));
  app.add_flag("--strict", run_options.strict, "fail (writing nothing) on any warning");
  const char* const network_help =
      "let inputs be URLs (/vsicurl/, https://...) and CRSs be fetched (off: local files only)";
  app.add_flag("--allow-network", run_options.allow_network, network_help);

  const CLI::Validator non_empty(
      [](const std::string& value) { return value.empty() ? std::string("empty path") : ""; },
      "PATH");

  PipelineArgs run_args;
  std::string out_dir;
  std::string backend;
  CLI::App* run = app.add_subcommand("run", "run a pipeline and write its layers");
  add_pipeline_args(*run, run_args);
  run->add_option("--out", out_dir, "output folder (replaces output.dir)")->check(non_empty);
  run->add_option("--backend", backend, "synthesis backend")
      ->check(CLI::IsMember({"cpu", "opencl", "auto"}));
  std::string cache_dir;
  run->add_option("--cache", cache_dir,
                  "cache folder: reuse the syntheses and tiles whose inputs are unchanged "
                  "(docs/cache.md; replaces the pipeline's cache key)")
      ->check(non_empty);

  PipelineArgs validate_args;
  CLI::App* validate =
      app.add_subcommand("validate", "parse a pipeline and check its inputs; writes nothing");
  add_pipeline_args(*validate, validate_args);

  CLI::App* schema = app.add_subcommand(
      "schema", "print the JSON Schema of pipeline files (docs/pipeline.schema.json; for editors)");

  std::string diff_a, diff_b;
  CLI::App* diff = app.add_subcommand(
      "diff", "what changed between two runs, layer by layer (exit 0: same, 1: different)");
  diff->add_option("RUN_A", diff_a, "output folder of a run")->required();
  diff->add_option("RUN_B", diff_b, "output folder of another run")->required();
  const char* const no_verify_help =
      "read the run's files as they are, without checking them against report.json's hashes";
  bool diff_no_verify = false;
  diff->add_flag("--no-verify", diff_no_verify, no_verify_help);

  tw::ViewOptions view_options;
  std::optional<int> serve_port;
  CLI::App* view = app.add_subcommand(
      "view", "write a self-contained 3D page of a run (three.js inlined; no network needed)");
  view->add_option("RUN_DIR", view_options.run_dir, "output folder of a run")->required();
  view->add_option("--out", view_options.out, "the page to write (default: RUN_DIR/view.html)");
  view->add_flag_function(
      "--no-verify", [&view_options](std::int64_t) { view_options.verify = false; },
      no_verify_help);
  view->add_option("--serve", serve_port,
                   "then serve its folder on 127.0.0.1:PORT until stopped (0: any free port)")
      ->expected(0, 1)
      ->default_str("8000")
      ->check(CLI::Range(0, 65535));
  tw::ViewServeOptions serve_options;
  view->add_option("--exemplar", serve_options.exemplar,
                   "with --serve: also serve network.html, drawing curve networks completed by "
                   "this exemplar (OGR path[:layer] or .svg)");
  view->add_option("--where", serve_options.where, "OGR SQL filter on the exemplar's layer");
  view->add_option("--scale", serve_options.scale, "SVG exemplar: metres per SVG unit")
      ->check(CLI::PositiveNumber);
  view->add_option("--seed", serve_options.seed, "the drawing page's growth seed");
  view->add_option("--save", serve_options.save,
                   "where the drawing page saves its lines (GeoPackage, layer lines; default "
                   "drawn_network.gpkg)");

  // A run in three steps for many processes or machines (docs/distributed.md).
  PipelineArgs plan_args;
  tw::PlanJobOptions plan_options;
  std::string plan_out;
  std::string plan_backend;
  CLI::App* plan = app.add_subcommand(
      "plan", "plan a pipeline's world and write its tasks (one per tile) for render-tile");
  add_pipeline_args(*plan, plan_args);
  plan->add_option("--out", plan_out, "output folder (replaces output.dir), shared by the workers")
      ->check(non_empty);
  plan->add_option("--backend", plan_backend, "synthesis backend")
      ->check(CLI::IsMember({"cpu", "opencl", "auto"}));
  std::string plan_cache;
  plan->add_option("--cache", plan_cache,
                   "cache folder for every task of the plan: reuse the syntheses and tiles whose "
                   "inputs are unchanged (docs/cache.md; replaces the pipeline's cache key)")
      ->check(non_empty);
  std::string plan_synthesis = "inline";
  plan->add_option("--synthesis", plan_synthesis,
                   "inline: synthesize here; tasks: leave each feature's synthesis to "
                   "synth-feature, then complete-plan (docs/distributed.md)")
      ->check(CLI::IsMember({"inline", "tasks"}));

  std::string synth_feature_plan;
  int synth_feature_index = 0;
  CLI::App* synth_feature = app.add_subcommand(
      "synth-feature", "synthesize one feature of a plan made with --synthesis tasks");
  synth_feature
      ->add_option("PLAN", synth_feature_plan, "plan folder, or the output folder holding one")
      ->required();
  synth_feature->add_option("--feature", synth_feature_index, "feature index (syntheses.json)")
      ->required()
      ->check(number_above(0.0, true));

  std::string complete_plan;
  CLI::App* complete = app.add_subcommand(
      "complete-plan", "put a plan's synthesized features into it, for render-tile");
  complete->add_option("PLAN", complete_plan, "plan folder, or the output folder holding one")
      ->required();

  std::string render_plan;
  int render_tile_index = 0;
  CLI::App* render_tile =
      app.add_subcommand("render-tile", "render one tile of a plan into its output folder");
  render_tile->add_option("PLAN", render_plan, "plan folder, or the output folder holding one")
      ->required();
  render_tile->add_option("--tile", render_tile_index, "tile index (tasks.json)")
      ->required()
      ->check(number_above(0.0, true));

  std::string finish_plan;
  CLI::App* finish = app.add_subcommand(
      "finish", "gather a plan's rendered tiles, write mosaics and report.json, and commit");
  finish->add_option("PLAN", finish_plan, "plan folder, or the output folder holding one")
      ->required();

  tw::SynthCommand synth_args;
  CLI::App* synth = app.add_subcommand(
      "synth", "synthesize a pattern along one curve into a PNG (the ribbon cage in red)");
  synth->add_option("--exemplar", synth_args.exemplar, "exemplar image with alpha")->required();
  synth
      ->add_option("--curve", synth_args.curve,
                   "line, arc, s-curve, circle, heart, hairpin, or an OGR source path[:layer]")
      ->required();
  synth->add_option("--length", synth_args.length, "size of a built-in shape, metres");
  synth->add_option("--width", synth_args.width,
                    "ribbon width b, metres (default: the exemplar's band, exemplar inspect)");
  synth->add_option("--delta", synth_args.delta,
                    "piece length, metres (default: the exemplar's suggested delta)");
  synth->add_option("--scale", synth_args.scale, "exemplar texels per metre")->required();
  synth->add_option("--backend", synth_args.backend, "cpu, opencl or auto")
      ->check(CLI::IsMember({"cpu", "opencl", "auto"}));
  synth->add_option("--seed", synth_args.seed, "0: the global optimum; else a seeded start");
  synth->add_option("-o,--output", synth_args.output, "PNG to write")->required();
  synth->add_option("--placements", synth_args.placements,
                    "also write the placements (JSON, docs/synthesis.md) to this file");
  synth
      ->add_option("--min-coverage", synth_args.min_coverage,
                   "fraction of each piece that must be opaque, in [0, 1) (0: the paper's rule; "
                   "default: a tenth of the exemplar's natural coverage)")
      ->check(number_above(0.0, true) & CLI::Range(0.0, 1.0));
  synth
      ->add_option_function<std::string>(
          "--objective",
          [&synth_args](const std::string& o) {
            synth_args.objective = o == "paper" ? tw::Objective::paper : tw::Objective::pattern;
          },
          "pattern (default: seams + a coverage term, a centred copy) or paper (seams alone)")
      ->check(CLI::IsMember({"pattern", "paper"}));
  synth
      ->add_option("--coverage-weight", synth_args.coverage_weight,
                   "pattern objective: weight of lost coverage against gamma (default 2)")
      ->check(CLI::Range(0.0, 1000.0));
  synth->add_flag("!--no-stitch", synth_args.stitch, "skip the edge alignment of Section 3.2");
  synth->add_option("--feather", synth_args.feather,
                    "metres either side of each seam where colours blend (0: exact copies)");
  synth
      ->add_option_function<std::string>(
          "--alpha",
          [&synth_args](const std::string& a) { synth_args.continuous_alpha = a == "continuous"; },
          "binary (opaque at alpha >= 0.5, the default) or continuous costs")
      ->check(CLI::IsMember({"binary", "continuous"}));

  tw::AreaCommand area_args;
  CLI::App* area = app.add_subcommand(
      "area",
      "fill polygons with a structured shape-pattern from a vector sketch (vectors, "
      "engine instances, preview)");
  area->add_option("sketch", area_args.sketch, "sketch: strokes in [0,1]^2 (GeoJSON, any OGR)")
      ->required();
  area->add_option("--polygons", area_args.polygons, "OGR source path[:layer], projected CRS")
      ->required();
  area->add_option("--where", area_args.where, "OGR SQL attribute filter on the polygons");
  area->add_option("--shapes-from", area_args.shapes_from,
                   "hybrid: a second sketch whose shapes go on the first one's rows");
  area->add_option("--scale", area_args.scale, "metres per sketch unit")
      ->check(number_above(0.0, false));
  area->add_option("--bearing", area_args.bearing,
                   "compass bearing (degrees) of the sketch's x axis; default: each polygon's "
                   "long axis")
      ->check(CLI::Range(-360.0, 360.0));
  area->add_option("--seed", area_args.seed, "same seed, same shapes");
  area->add_option("--jitter", area_args.jitter, "fraction of the allowed displacement used")
      ->check(CLI::Range(0.0, 1.0));
  area->add_option("--avoid", area_args.avoid,
                   "features no shape may touch: OGR path[:layer] (lines or polygons; repeatable)");
  area->add_option("--avoid-width", area_args.avoid_width,
                   "metres, the width of avoided lines without a width or OSM tags")
      ->check(number_above(0.0, false));
  area->add_option("--resolution", area_args.resolution,
                   "metres per cell of the avoidance lattice; strokes are written within a "
                   "quarter of it")
      ->check(number_above(0.0, false));
  area->add_option("--analysis-png", area_args.analysis_png,
                   "also draw the sketch's analysis levels (strokes, shapes, fibres, medians, "
                   "lead directions) into this PNG");
  area->add_option("--out", area_args.out, "folder for shapes.gpkg, instances.csv, preview.png")
      ->required()
      ->check(non_empty);

  tw::GrowCommand grow_args;
  CLI::App* grow = app.add_subcommand(
      "grow",
      "grow FloralSurf ornaments (hedges, terrace walls, trails, ditches) over a region of a "
      "DEM (lines with heights, preview)");
  grow->add_option("--dem", grow_args.dem, "heightfield: any raster GDAL reads")->required();
  grow->add_option("--region", grow_args.region,
                   "minx,miny,maxx,maxy in the DEM's CRS, or OGR polygons path[:layer]")
      ->required();
  grow->add_option("--where", grow_args.where, "OGR SQL attribute filter on the region");
  grow->add_option("--element", grow_args.element, "element set (samples/ornaments/*.json)")
      ->required();
  grow->add_option("--avoid", grow_args.avoid,
                   "features no ornament may enter: OGR path[:layer] (lines or polygons; "
                   "repeatable)");
  grow->add_option("--avoid-width", grow_args.avoid_width,
                   "metres, the width of avoided lines without a width or OSM tags")
      ->check(number_above(0.0, false));
  grow->add_option("--resolution", grow_args.resolution,
                   "metres between mesh vertices (the DEM resampled, cubic); default: the DEM's")
      ->check(number_above(0.0, false));
  grow->add_option("--seed", grow_args.seed, "same seed, same ornaments");
  grow->add_flag("--contour", grow_args.contour,
                 "align elements to the contour direction (terraces along the slope)");
  grow->add_flag("--first-fit", grow_args.first_fit,
                 "take the first candidate that fits (the greedy variant) instead of the best");
  grow->add_option("--trials", grow_args.trials, "candidates per growth point")
      ->check(CLI::Range(1, 1000));
  grow->add_option("--max-ornaments", grow_args.max_ornaments, "ornaments started at most")
      ->check(CLI::Range(1, 100000));
  grow->add_option("--clearance", grow_args.clearance,
                   "metres between unrelated lines; default: the element set's clearance_m")
      ->check(number_above(0.0, true));
  grow->add_option("--coverage-radius", grow_args.coverage_radius,
                   "metres for the reported coverage; default: half the element set's scale")
      ->check(number_above(0.0, false));
  grow->add_option("--out", grow_args.out, "folder for ornaments.gpkg, preview.png")
      ->required()
      ->check(non_empty);

  tw::NetworkCommand network_args;
  CLI::App* network = app.add_subcommand(
      "network",
      "curve networks by example (hedges, field edges, drainage, terraces): synthesize over a "
      "region, complete a partial drawing, or clone one region's structure into another");
  network->require_subcommand(1);
  CLI::App* network_modes[3] = {
      network->add_subcommand("synthesize",
                              "grow a network with the exemplar's style over --region"),
      network->add_subcommand("complete",
                              "complete --partial (kept exactly as drawn) over --region in the "
                              "exemplar's style"),
      network->add_subcommand("clone",
                              "grow --map's structure inside --source-region into --target-region, "
                              "keeping what is there")};
  for (CLI::App* mode : network_modes) {
    if (std::string(mode->get_name()) != "clone") {
      mode->add_option("--exemplar", network_args.exemplar,
                       "exemplar lines: OGR path[:layer] (GeoPackage, GeoJSON, Shapefile, OSM) or "
                       "an .svg")
          ->required();
      mode->add_option("--exemplar-region", network_args.exemplar_region,
                       "polygons cutting the exemplar out of a real map: OGR path[:layer]");
      mode->add_option("--region", network_args.region,
                       "minx,miny,maxx,maxy in the exemplar's CRS, or OGR polygons path[:layer]")
          ->required();
    } else {
      mode->add_option("--map", network_args.map, "the map's lines: OGR path[:layer]")->required();
      mode->add_option("--source-region", network_args.source_region,
                       "polygons whose lines are the exemplar (path[:layer] or a box)")
          ->required();
      mode->add_option("--target-region", network_args.target_region,
                       "polygons (path[:layer]) or minx,miny,maxx,maxy to grow into")
          ->required();
    }
    if (std::string(mode->get_name()) == "complete")
      mode->add_option("--partial", network_args.partial,
                       "the lines drawn so far: OGR path[:layer] or .svg, kept exactly")
          ->required();
    mode->add_option("--where", network_args.exemplar_where,
                     "OGR SQL attribute filter on the exemplar's (or map's) layer");
    mode->add_option("--scale", network_args.scale, "SVG: metres per SVG unit")
        ->check(number_above(0.0, false));
    mode->add_option("--avoid", network_args.avoid,
                     "features no curve may enter: OGR path[:layer] (lines or polygons; "
                     "repeatable)");
    mode->add_option("--avoid-width", network_args.avoid_width,
                     "metres, the width of avoided lines without a width or OSM tags")
        ->check(number_above(0.0, false));
    mode->add_option("--seed", network_args.growth.seed, "same seed, same network");
    mode->add_option("--lead-bearing", network_args.growth.lead_bearing,
                     "compass degrees the exemplar's main bearing is turned to");
    mode->add_option("--lead", network_args.lead,
                     "long_axis: the exemplar's main bearing is turned to the region's long axis "
                     "(its largest polygon's), as a pipeline's `lead: long_axis`");
    mode->add_option("--clearance", network_args.growth.clearance,
                     "metres between unrelated curves; default: 6 % of the median edge length")
        ->check(number_above(0.0, true));
    mode->add_option("--snap", network_args.snap,
                     "metres: exemplar ends this close to a line are joined to it (repair); "
                     "default: 1e-3 of its extent")
        ->check(number_above(0.0, true));
    mode->add_option("--candidates", network_args.growth.candidates, "pieces tried per stub")
        ->check(CLI::Range(1, 1000));
    mode->add_option_function<std::string>(
            "--method",
            [&network_args](const std::string& name) {
              network_args.growth.method = tw::network_method_named(name);
            },
            "growth, quilt, layout (growth from the exemplar's long strokes), or automatic "
            "(default): each, and the one closer to the exemplar's statistics; completing lines "
            "is growth (quilt and layout refused)")
        ->check(CLI::IsMember(std::vector<std::string>(tw::kNetworkMethodNames.begin(),
                                                       tw::kNetworkMethodNames.end())));
    mode->add_option("--out", network_args.out, "folder for network.gpkg, preview.png")
        ->required()
        ->check(non_empty);
  }

  // Hidden (no group): the generated world of bench/bigworld.sh.
  tw::BigWorldOptions world;
  CLI::App* make_world =
      app.add_subcommand("make-world", "write a generated world for benchmarks")->group("");
  make_world->add_option("--size", world.size, "cells per side")->required();
  make_world->add_option("--pixel", world.pixel_size, "metres per cell");
  make_world->add_option("--seed", world.seed, "terrain and network seed");
  make_world->add_option("--tile", world.tile_size, "output.tiles.size of world.yaml");
  make_world->add_option("--overlap", world.tile_overlap, "output.tiles.overlap of world.yaml");
  make_world->add_option("--out", world.dir, "folder to write")->required();

  tw::ExemplarInspectCommand inspect_args;
  CLI::App* exemplar = app.add_subcommand("exemplar", "what an exemplar implies for synthesis");
  exemplar->require_subcommand(1);
  CLI::App* inspect = exemplar->add_subcommand(
      "inspect", "opaque rows, period, suggested delta, coverage, cyclic; optional preview PNG");
  inspect->add_option("image", inspect_args.exemplar, "exemplar image with alpha")->required();
  inspect->add_option("--preview", inspect_args.preview,
                      "PNG with the band (blue), centre (green), period ticks (red), coverage");
  inspect->add_flag("--json", inspect_args.json, "one JSON object instead of text");
  inspect->add_flag("--allow-network", inspect_args.allow_network, network_help);
  tw::ExportCommand export_args;
  std::string export_engine;
  CLI::App* export_run = app.add_subcommand(
      "export", "turn a finished run into an engine's heightmap, weightmaps and splines");
  export_run->add_option("RUN_DIR", export_args.run_dir, "output folder of a run")->required();
  export_run->add_option("--to", export_engine, "unreal, unity, godot (HTerrain) or terrain3d")
      ->required()
      ->check(CLI::IsMember({"unreal", "unity", "godot", "terrain3d"}));
  export_run->add_option("--out", export_args.out_dir, "folder to write")
      ->required()
      ->check(non_empty);
  export_run->add_option(
      "--size", export_args.options.size,
      "heightmap samples per side (default: the smallest size holding the world; Unreal: any "
      "from 8 to 8129, a warning when not one of Epic's recommended sizes)");
  export_run->add_option("--input-height", export_args.input_height,
                         "the heights before the run (the pipeline's DEM, or a raster on the run's "
                         "grid): also write the non-destructive layers (height delta, weights)");
  export_run->add_flag_function(
      "--no-verify", [&export_args](std::int64_t) { export_args.verify = false; }, no_verify_help);
  export_run
      ->add_option("--tile-size", export_args.options.tile_size,
                   "samples per tile (Unreal World Partition, Unity; 0: one heightmap; "
                   "default: tiles when the run is tiled)")
      ->check(number_above(0.0, true));
  export_run->add_option("--nodata-height", export_args.options.nodata_height,
                         "metres written on nodata (default: the nearest valid heights)");
  export_run
      ->add_option_function<std::string>(
          "--godot-height",
          [&export_args](const std::string& f) {
            export_args.options.godot_height =
                f == "r16" ? tw::GodotHeightFormat::r16 : tw::GodotHeightFormat::exr;
          },
          "godot and terrain3d: exr (32-bit float metres, the default) or r16")
      ->check(CLI::IsMember({"exr", "r16"}));

  list_global_options_in_subcommand_help(app);
  refuse_non_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // one line, whatever the arguments held
    std::fprintf(stderr, "terraweave: usage error: %s (see terraweave --help)\n",
                 tw::single_line(e.what()).c_str());
    return 2;
  }

  tw::set_log_level(verbose ? spdlog::level::debug
                    : quiet ? spdlog::level::warn
                            : spdlog::level::info);
  try {
    if (run->parsed()) {
      if (run->count("--out")) run_options.output_dir = out_dir;
      if (!backend.empty()) run_options.backend = backend;
      if (run->count("--cache")) run_options.cache_dir = cache_dir;
      return run_command(run_args, run_options);
    }
    if (validate->parsed()) return validate_command(validate_args, run_options);
    if (schema->parsed()) {
      std::fputs(tw::pipeline_schema_json().c_str(), stdout);
      return 0;
    }
    if (diff->parsed()) {
      try {
        return diff_command(diff_a, diff_b, !diff_no_verify);
      } catch (const std::exception& e) {
        std::fflush(stdout);
        std::fprintf(stderr, "terraweave: error: %s\n", tw::single_line(e.what()).c_str());
        return 2;
      }
    }
    if (view->parsed()) {
      if (view->count("--serve") == 0)
        for (const char* option : {"--exemplar", "--where", "--scale", "--seed", "--save"})
          if (view->count(option) > 0) tw::fail("view: {} needs --serve", option);
      if (serve_options.exemplar.empty())
        for (const char* option : {"--where", "--scale", "--seed", "--save"})
          if (view->count(option) > 0) tw::fail("view: {} needs --exemplar", option);
      serve_options.port = serve_port.value_or(8000);
      return view_command(view_options, view->count("--serve") > 0, serve_options);
    }
    if (area->parsed()) {
      area_args.strict = run_options.strict;  // the global flag
      const tw::AreaCommandResult r = tw::run_area_command(area_args);
      std::printf(
          "%d instances, %d strokes in %d polygons (left out: %d outside, %d forbidden, "
          "%d overlapping)\n",
          r.instances, r.strokes, r.polygons, r.outside, r.forbidden, r.overlapping);
      return 0;
    }
    if (grow->parsed()) {
      grow_args.strict = run_options.strict;  // the global flag
      const tw::GrowCommandResult r = tw::run_grow_command(grow_args);
      std::printf(
          "%d ornaments, %d elements, %d lines; coverage within %.1f m: %.3f (rejected: %d "
          "crossing, %d forbidden, %d onto a footprint, %d off the window); %lld crossings\n",
          r.ornaments, r.elements, r.lines, r.coverage_radius, r.coverage, r.rejected_crossing,
          r.rejected_forbidden, r.rejected_footprint, r.rejected_untraceable,
          static_cast<long long>(r.crossings.total()));
      return 0;
    }
    if (network->parsed()) {
      for (CLI::App* mode : network_modes)
        if (mode->parsed()) network_args.mode = mode->get_name();
      const tw::NetworkCommandResult r = tw::run_network_command(network_args);
      std::printf("%s\n", tw::network_command_summary(r).c_str());
      return 0;
    }
    if (make_world->parsed()) {
      const tw::BigWorldSummary s = tw::write_big_world(world);
      std::printf("%d roads %.1f km, %d rivers %.1f km, %.1f km^2\n", s.roads, s.road_km, s.rivers,
                  s.river_km, s.area_km2);
      return 0;
    }
    if (inspect->parsed()) {
      std::fputs(tw::run_exemplar_inspect(inspect_args).c_str(), stdout);
      return 0;
    }
    if (export_run->parsed()) {
      export_args.options.engine = tw::parse_engine(export_engine);
      const tw::EngineExportResult result = tw::run_export_command(export_args);
      for (const std::string& line : result.warnings) tw::logger().warn("{}", line);
      for (const std::string& line : result.settings) std::printf("%s\n", line.c_str());
      std::printf("%zu files in %s\n", result.files.size(),
                  tw::single_line(export_args.out_dir.string()).c_str());
      return 0;
    }
    if (plan->parsed()) {
      if (!plan_out.empty()) plan_options.output_dir = plan_out;
      if (!plan_backend.empty()) plan_options.backend = plan_backend;
      if (!plan_cache.empty()) plan_options.cache_dir = plan_cache;
      plan_options.synthesis_tasks = plan_synthesis == "tasks";
      plan_options.strict = run_options.strict;  // the global flags
      plan_options.allow_network = run_options.allow_network;
      return plan_command(plan_args, plan_options);
    }
    if (synth_feature->parsed())
      return synth_feature_command(synth_feature_plan, synth_feature_index);
    if (complete->parsed()) return complete_plan_command(complete_plan, run_options.strict);
    if (render_tile->parsed()) return render_tile_command(render_plan, render_tile_index);
    if (finish->parsed()) return finish_command(finish_plan);
    if (synth->parsed()) {
      synth_args.allow_network = run_options.allow_network;
      const tw::Synthesis result = tw::run_synth_command(synth_args);
      std::printf("%zu pieces, Omega %lld, %.2f per seam (%.2f stitched), backend %s\n",
                  result.placements.size(), static_cast<long long>(result.total_cost),
                  result.mean_seam_cost, result.mean_seam_cost_stitched, result.backend.c_str());
      return 0;
    }
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "terraweave: error: %s\n", tw::single_line(e.what()).c_str());
    return 1;
  }
  return 2;
}

}  // namespace
