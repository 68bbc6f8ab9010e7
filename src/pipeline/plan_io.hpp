#pragma once
// A WorldPlan as a folder of files (docs/distributed.md, "The plan folder"), so that tiles
// render in other processes and on other machines:
//   <dir>/plan.json            grid, output window (a region's), CRS, tiling, render options,
//                              class names, materials, the heights' source (a DEM file by path,
//                              options and XXH3-128 of its bytes; a generated world by its
//                              parameters), and the list of object files with their content hashes
//   <dir>/tasks.json           one task per tile: index, _x/_y, window and halo window
//   <dir>/objects/<hash>.bin   settings, lines, ribbons, junctions, existing features, terrain
//                              plan, indexes, heights (only when held in memory), the plan's
//                              report: values as bytes (detail/plan_binary.hpp), the ribbons
//                              with an offset table so a tile decodes only those that reach it
//   <dir>/objects/<hash>.cbor  what each synthesis method stores of its entry (`methods` in
//                              plan.json: areas' shapes, exemplars' texels, grown lines...)
//   <dir>/objects/<hash>.json  one pattern's placements (synth/placements_io)
// <hash> is the XXH3-128 of the file's bytes: a file is never trusted if it does not match, and
// an unchanged object keeps its name from one plan to the next. The plan's own hash (`plan`
// in plan.json and tasks.json) covers everything, so a tile result names the plan it belongs to.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/plan.hpp"

namespace tw {

inline constexpr const char* kPlanFormat = "terraweave.plan";
inline constexpr const char* kTasksFormat = "terraweave.tasks";
// 3: the grown classes (files.grown); 4: their short_lines and synthesis counts; 5:
// synthesis_junctions (choose: mix); 6: tasks.json's hash in plan.json, syntheses.json's in
// job.json, a mix's report fields (issue #24); 7: a network class's report (`network`); 8: one
// entry per synthesis method (`methods`: name, index, the method's own entry) in place of
// area_names, exemplars, patterns and files.areas/grown/index.patterns/index.areas; 9: the
// plan's own objects and the methods' indexes as binary objects (.bin) in place of CBOR; 10:
// the patterns' exemplars and patterns (with their placements) as binary objects too; 11: the
// methods' parts of the report (a feature's synthesis, a class's grow and network, the areas)
// stored by their methods, as methods[].report, in place of fields of the report's object; 12:
// the report's object without the methods' JSON parts (every method reports through its part);
// 13: a network class's `lead` and `lead_bearing_deg`.
inline constexpr int kPlanVersion = 13;

// Writes the plan into `dir` (created; objects of an earlier plan there that this one does not
// use are deleted; plan.json and tasks.json are replaced atomically, last). Returns the plan's
// hash. Throws tw::Error naming the file that cannot be written.
std::string save_plan(const WorldPlan& plan, const std::filesystem::path& dir);

// Reads a plan written by save_plan. Throws tw::Error naming the file and the key when a file
// is missing, malformed, of another format version, or does not match its content hash: the
// objects, tasks.json (its hash in plan.json) and plan.json's own fields (the plan's hash,
// recomputed), with the command that plans again.
// `methods`: the synthesis methods whose entries it reads (empty: the built-in ones); an entry of
// a method not among them is an error naming it.
WorldPlan load_plan(const std::filesystem::path& dir,
                    const std::vector<const SynthesisMethod*>& methods = {});

// The plan as render_tile needs it for tile `tile` (tasks.json), checked as load_plan checks it:
// the ribbons that cannot reach the tile's halo window (WorldPlan::ribbon_index grown by
// avoidance_halo_pixels) are left empty, so its decoding follows the tile, not the world; the
// syntheses' inputs (synthesis_junction_discs, synthesis_junctions) and the report are not read.
// Only for rendering that tile. Throws tw::Error when the plan has no such tile.
WorldPlan load_plan_for_tile(const std::filesystem::path& dir, int tile,
                             const std::vector<const SynthesisMethod*>& methods = {});

// The plan's hash as plan.json records it (without reading the objects).
std::string plan_hash(const std::filesystem::path& dir);

// A JSON file of the plan folder (plan.json, tasks.json, job.json, tile results): throws
// tw::Error naming the file unless it parses, has this `format` and this version.
nlohmann::json read_plan_file(const std::filesystem::path& path, const char* format);

}  // namespace tw
