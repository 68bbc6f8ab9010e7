// terraweave's command line: a thin parse over library calls (pipeline/, synth/).
// Every tw::Error becomes one line "terraweave: error: <message>" (newlines escaped) and exit
// code 1; usage errors are one line "terraweave: usage error: ..." and exit with 2.
#include <cpl_error.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/config.hpp"
#include "pipeline/job.hpp"
#include "pipeline/run.hpp"
#include "pipeline/synth_command.hpp"
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
};

void add_pipeline_args(CLI::App& command, PipelineArgs& args) {
  command.add_option("PIPELINE", args.file, "pipeline file (YAML, see docs/pipeline.md)")
      ->required();
  command.add_option("--set", args.overrides,
                     "override a value of the pipeline file: key.path=value (repeatable)");
}

tw::PipelineConfig load(const PipelineArgs& args) {
  std::vector<tw::Override> overrides;
  for (const std::string& o : args.overrides) overrides.push_back(tw::parse_override(o));
  return tw::load_pipeline(args.file, overrides);
}

int run_command(const PipelineArgs& args, const tw::RunOptions& options) {
  const tw::RunReport report = tw::run_pipeline(load(args), options);
  for (const auto& stage : report.stages)
    std::printf("%-10s %8.3f s\n", stage.stage.c_str(), stage.seconds);
  if (!report.warnings.empty()) std::printf("%-10s %8zu\n", "warnings", report.warnings.size());
  std::printf("%-10s %8.3f s, %zu files in %s\n", "total", report.total_seconds,
              report.outputs.size(),
              report.outputs.empty()
                  ? "-"
                  : tw::single_line(report.outputs.front().parent_path().string()).c_str());
  return 0;
}

int validate_command(const PipelineArgs& args, bool strict, bool allow_network) {
  tw::RunOptions options;
  options.write_outputs = false;
  options.strict = strict;
  options.allow_network = allow_network;
  const tw::RunReport report = tw::run_pipeline(load(args), options);
  std::size_t features = 0;
  for (const auto& c : report.classes) features += c.features.size();
  std::printf("%s: ok (%zu feature classes, %zu features, grid %d x %d, %zu warnings)\n",
              tw::single_line(args.file).c_str(), report.classes.size(), features,
              report.grid.width, report.grid.height, report.warnings.size());
  return 0;
}

int plan_command(const PipelineArgs& args, tw::PlanJobOptions options) {
  options.overrides = args.overrides;
  const tw::PipelineConfig config = load(args);
  if (options.output_dir.empty()) options.output_dir = config.output.dir;
  const tw::PlannedJob job = tw::plan_job(config, options);
  std::printf("plan %s: %zu tiles, %zu warnings, in %s\n", job.plan.c_str(), job.tiles,
              job.warnings, tw::single_line(job.plan_dir.string()).c_str());
  return 0;
}

int render_tile_command(const std::string& plan, int tile) {
  const tw::TileJobResult result = tw::render_job_tile(tw::find_plan_dir(plan), tile);
  std::printf("tile %d: %zu files in %.3f s\n", result.tile, result.files.size(), result.seconds);
  return 0;
}

int finish_command(const std::string& plan) {
  const tw::RunReport report = tw::finish_job(tw::find_plan_dir(plan));
  std::printf("%zu files in %s\n", report.outputs.size(),
              report.outputs.empty()
                  ? "-"
                  : tw::single_line(report.outputs.front().parent_path().string()).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CPLSetErrorHandler(log_gdal_message);
  CLI::App app{"terraweave: terrain features for procedural worlds"};
  app.require_subcommand(1);
  app.set_version_flag("--version", tw::version_line());
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "debug logging");
  app.add_flag("-q,--quiet", quiet, "warnings and errors only");

  const CLI::Validator non_empty(
      [](const std::string& value) { return value.empty() ? std::string("empty path") : ""; },
      "PATH");

  PipelineArgs run_args;
  tw::RunOptions run_options;
  std::string out_dir;
  std::string backend;
  CLI::App* run = app.add_subcommand("run", "run a pipeline and write its layers");
  add_pipeline_args(*run, run_args);
  run->add_option("--out", out_dir, "output folder (replaces output.dir)")->check(non_empty);
  run->add_option("--backend", backend, "synthesis backend")
      ->check(CLI::IsMember({"cpu", "opencl", "auto"}));
  run->add_option("--threads", run_options.threads, "worker threads (default: every core)")
      ->check(CLI::Range(1, tw::kMaxThreads));
  run->add_flag("--strict", run_options.strict, "fail (writing nothing) on any warning");
  const char* const network_help =
      "let inputs be URLs (/vsicurl/, https://...) and CRSs be fetched (off: local files only)";
  run->add_flag("--allow-network", run_options.allow_network, network_help);

  PipelineArgs validate_args;
  bool validate_strict = false;
  CLI::App* validate =
      app.add_subcommand("validate", "parse a pipeline and check its inputs; writes nothing");
  add_pipeline_args(*validate, validate_args);
  validate->add_flag("--strict", validate_strict, "fail on any warning");
  bool validate_allow_network = false;
  validate->add_flag("--allow-network", validate_allow_network, network_help);

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
  plan->add_flag("--strict", plan_options.strict, "fail (writing nothing) on any warning");
  plan->add_flag("--allow-network", plan_options.allow_network, network_help);

  std::string render_plan;
  int render_tile_index = 0;
  CLI::App* render_tile =
      app.add_subcommand("render-tile", "render one tile of a plan into its output folder");
  render_tile->add_option("PLAN", render_plan, "plan folder, or the output folder holding one")
      ->required();
  render_tile->add_option("--tile", render_tile_index, "tile index (tasks.json)")
      ->required()
      ->check(CLI::NonNegativeNumber);

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
  synth->add_option("--width", synth_args.width, "ribbon width b, metres")->required();
  synth->add_option("--delta", synth_args.delta, "piece length, metres")->required();
  synth->add_option("--scale", synth_args.scale, "exemplar texels per metre")->required();
  synth->add_option("--backend", synth_args.backend, "cpu, opencl or auto")
      ->check(CLI::IsMember({"cpu", "opencl", "auto"}));
  synth->add_option("--seed", synth_args.seed, "0: the global optimum; else a seeded start");
  synth->add_option("-o,--output", synth_args.output, "PNG to write")->required();
  synth->add_option("--placements", synth_args.placements,
                    "also write the placements (JSON, docs/synthesis.md) to this file");
  synth->add_option("--min-coverage", synth_args.min_coverage,
                    "fraction of each piece that must be opaque, in [0, 1) (0: the paper's rule)");
  synth->add_flag("!--no-stitch", synth_args.stitch, "skip the edge alignment of Section 3.2");
  synth->add_flag("--allow-network", synth_args.allow_network, network_help);
  synth->add_option("--feather", synth_args.feather,
                    "metres either side of each seam where colours blend (0: exact copies)");
  synth
      ->add_option_function<std::string>(
          "--alpha",
          [&synth_args](const std::string& a) { synth_args.continuous_alpha = a == "continuous"; },
          "binary (opaque at alpha >= 0.5, the default) or continuous costs")
      ->check(CLI::IsMember({"binary", "continuous"}));

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
      return run_command(run_args, run_options);
    }
    if (plan->parsed()) {
      if (!plan_out.empty()) plan_options.output_dir = plan_out;
      if (!plan_backend.empty()) plan_options.backend = plan_backend;
      return plan_command(plan_args, plan_options);
    }
    if (render_tile->parsed()) return render_tile_command(render_plan, render_tile_index);
    if (finish->parsed()) return finish_command(finish_plan);
    if (validate->parsed())
      return validate_command(validate_args, validate_strict, validate_allow_network);
    if (synth->parsed()) {
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
