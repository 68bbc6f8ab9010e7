// Godot 4 / Terrain3D: the world's cells as they are (Terrain3D takes any size and slices it
// into regions itself; one vertex per cell, vertex_spacing = the cell size, so no resampling),
// heights as a 32-bit float EXR in metres (or R16 with min and max), Terrain3D's packed 32-bit
// control map (base texture = the heaviest material, overlay = the second, blend = the
// overlay's share of the two) as the float-typed EXR its importer reads, the region size and
// import position that fit the world into Terrain3D's 32 x 32 region map, and a GDScript that
// imports it all through Terrain3D's API (docs/exports.md, "Godot 4: Terrain3D").
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/splines.hpp"

namespace tw::detail {

namespace {

// Terrain3D's control map bits (doc/docs/controlmap_format.md of Terrain3D): base texture id
// in bits 31-27, overlay id in 26-22, blend in 21-14 (0: all base, 255: all overlay); UV angle
// (13-10), UV scale (9-7), hole (2), navigation (1) and autoshader (0) are left 0.
std::uint32_t control_bits(std::uint32_t base, std::uint32_t overlay, std::uint32_t blend) {
  return (base & 0x1Fu) << 27 | (overlay & 0x1Fu) << 22 | (blend & 0xFFu) << 14;
}

// Per cell: the heaviest material (lowest index on ties) is the base, the next heaviest the
// overlay, blend = round(255 x overlay / (base + overlay)); a single material is its own
// overlay with blend 0, a cell without weight is material 0.
std::vector<float> control_map(const Layer* splat, int width, int height) {
  std::vector<float> out(std::size_t(width) * height, std::bit_cast<float>(control_bits(0, 0, 0)));
  if (splat == nullptr) return out;
  const std::size_t n = splat->bands.size();
  for (std::size_t p = 0; p < out.size(); ++p) {
    std::size_t first = 0, second = 0;
    double w1 = -1.0, w2 = -1.0;
    for (std::size_t m = 0; m < n; ++m) {
      const float raw = splat->bands[m].pixels[p];
      const double w = std::isfinite(raw) && raw > 0.0f ? double(raw) : 0.0;
      if (w > w1) {
        second = first;
        w2 = w1;
        first = m;
        w1 = w;
      } else if (w > w2) {
        second = m;
        w2 = w;
      }
    }
    std::uint32_t blend = 0;
    if (w2 > 0.0)
      blend = std::uint32_t(std::lround(255.0 * w2 / (w1 + w2)));
    else
      second = first;
    out[p] = std::bit_cast<float>(control_bits(std::uint32_t(first), std::uint32_t(second), blend));
  }
  return out;
}

// Terrain3D's region sizes (Terrain3D::RegionSize) and its region map of 32 x 32 regions.
constexpr int kRegionMap = 32;
constexpr int kMinRegionSize = 256;  // Terrain3D's default
constexpr int kMaxRegionSize = 2048;

// The default region size when the world fits 32 regions of it per side, else the smallest
// power of two that fits it.
int region_size_for(int samples) {
  int size = kMinRegionSize;
  while (size * kRegionMap < samples && size < kMaxRegionSize) size *= 2;
  if (size * kRegionMap < samples)
    fail("export terrain3d: {} samples per side do not fit Terrain3D's {} regions of {}", samples,
         kRegionMap, kMaxRegionSize);
  return size;
}

// A float literal GDScript types as float (6.0, not the int 6), round-tripping the double.
std::string gdscript_float(double v) {
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string import_script(const nlohmann::json& sidecar) {
  // Runs in the editor (File > Run, with a scene holding a Terrain3D node selected, or attached to
  // an EditorScript): the same calls as Terrain3D's own importer (tools/importer.gd).
  return fmt::format(
      R"(@tool
extends EditorScript
# Imports a terraweave export into the selected Terrain3D node (Terrain3D 1.0+, Godot 4): copy
# the export folder into the project, open this script, Script editor > File > Run, with the
# Terrain3D node selected in the scene tree. Written by terraweave export --to terrain3d; the
# numbers are those of terrain3d.json.

const REGION_SIZE := {region}
const VERTEX_SPACING := {spacing}
const IMPORT_POSITION := Vector2i({px}, {pz})  # in vertices, a whole number of regions
const HEIGHT_FILE := "{height}"
const R16_RANGE := Vector2({r16min}, {r16max})  # only read for a .r16 height file
const R16_SIZE := Vector2i({w}, {h})

func here() -> String:
	return get_script().resource_path.get_base_dir()

func _run() -> void:
	var terrain: Terrain3D = null
	for node in EditorInterface.get_selection().get_selected_nodes():
		if node is Terrain3D:
			terrain = node
	if terrain == null:
		push_error("select a Terrain3D node first")
		return
	terrain.change_region_size(REGION_SIZE)
	terrain.vertex_spacing = VERTEX_SPACING
	var images: Array[Image] = []
	images.resize(Terrain3DRegion.TYPE_MAX)
	images[Terrain3DRegion.TYPE_HEIGHT] = Terrain3DUtil.load_image(here().path_join(HEIGHT_FILE),
			ResourceLoader.CACHE_MODE_IGNORE, R16_RANGE, R16_SIZE)
	images[Terrain3DRegion.TYPE_CONTROL] = Terrain3DUtil.load_image(here().path_join("control.exr"),
			ResourceLoader.CACHE_MODE_IGNORE)
	var position := Vector3(IMPORT_POSITION.x, 0, IMPORT_POSITION.y) * VERTEX_SPACING
	terrain.data.import_images(images, position, 0.0, 1.0)
	print("terraweave: imported %s at %s" % [here(), position])

# Layers over an existing terrain (export with --input-height): adds layers/height_delta.exr to
# the heights already there and writes the control bits where the features painted.
func apply_layers(terrain: Terrain3D) -> void:
	var delta := Terrain3DUtil.load_image(here().path_join("layers/height_delta.exr"),
			ResourceLoader.CACHE_MODE_IGNORE)
	var control := Terrain3DUtil.load_image(here().path_join("control.exr"),
			ResourceLoader.CACHE_MODE_IGNORE)
	var origin := Vector3(IMPORT_POSITION.x, 0, IMPORT_POSITION.y) * VERTEX_SPACING
	for z in delta.get_height():
		for x in delta.get_width():
			var p := origin + Vector3(x, 0, z) * VERTEX_SPACING
			var d := delta.get_pixel(x, z).r
			if d != 0.0:
				terrain.data.set_height(p, terrain.data.get_height(p) + d)
			var bits := Terrain3DUtil.as_uint(control.get_pixel(x, z).r)
			if Terrain3DUtil.get_base(bits) != 0 or Terrain3DUtil.get_blend(bits) != 0:
				terrain.data.set_control(p, bits)
	terrain.data.update_maps()
)",
      fmt::arg("region", sidecar["region_size"].get<int>()),
      fmt::arg("spacing", gdscript_float(sidecar["vertex_spacing"].get<double>())),
      fmt::arg("px", sidecar["import_position"][0].get<int>()),
      fmt::arg("pz", sidecar["import_position"][1].get<int>()),
      fmt::arg("height", sidecar["height"].get<std::string>()),
      fmt::arg("r16min", gdscript_float(sidecar["height_min_m"].get<double>())),
      fmt::arg("r16max", gdscript_float(sidecar["height_max_m"].get<double>())),
      fmt::arg("w", sidecar["size"][0].get<int>()), fmt::arg("h", sidecar["size"][1].get<int>()));
}

}  // namespace

EngineExportResult export_terrain3d(const ExportSource& source, const EngineExportOptions& options,
                                    const std::filesystem::path& dir, OutputStager& stager) {
  const GridSpec& grid = source.set.grid;
  if (options.size != 0)
    fail("export terrain3d: no --size: Terrain3D takes the world's {} x {} cells as they are",
         grid.width, grid.height);
  if (grid.pixel_width != grid.pixel_height)
    fail("export terrain3d: the run's cells are {} x {} m; Terrain3D's vertices are square",
         grid.pixel_width, grid.pixel_height);
  if (source.splat != nullptr && source.splat->bands.size() > 32)
    fail("export terrain3d: {} materials; Terrain3D's control map holds texture ids 0 ... 31",
         source.splat->bands.size());
  const double spacing = grid.pixel_width;
  const int region = region_size_for(std::max(grid.width, grid.height));
  const int regions_x = (grid.width + region - 1) / region;
  const int regions_z = (grid.height + region - 1) / region;
  // The world centred on the origin, on whole regions: regions -k/2 ... k - k/2 - 1.
  const int import_x = -(regions_x / 2) * region, import_z = -(regions_z / 2) * region;

  EngineExportResult result;
  if (spacing < 0.25 || spacing > 100.0)
    result.warnings.push_back(fmt::format(
        "terrain3d: the cell size {} m is outside Terrain3D's vertex_spacing 0.25 ... 100; it "
        "clamps it, so the terrain will not be to scale",
        spacing));
  const Heightmap16 map = quantize_heights(source.heights);
  const bool exr = options.godot_height == GodotHeightFormat::exr;
  const std::string height_file = exr ? "height.exr" : "height.r16";
  result.files.push_back(dir / height_file);
  if (exr)
    write_float_exr(stager.stage(result.files.back()), grid.width, grid.height,
                    source.heights.pixels.data());
  else
    write_raw16(stager.stage(result.files.back()), map, false);
  const std::vector<float> control = control_map(source.splat, grid.width, grid.height);
  result.files.push_back(dir / "control.exr");
  write_float_exr(stager.stage(result.files.back()), grid.width, grid.height, control.data());

  const std::vector<std::string> names =
      source.splat ? material_names(source.splat->channels) : std::vector<std::string>{"base"};
  nlohmann::json textures = nlohmann::json::array();
  for (std::size_t m = 0; m < names.size(); ++m)
    textures.push_back({{"id", m}, {"material", names[m]}});
  // Splines: Godot's frame (x east, y up, z south) moved to where the import puts the world.
  EngineFrame frame = engine_frame(Engine::godot, grid);
  frame.engine = "terrain3d";
  const double shift_x = import_x * spacing, shift_z = import_z * spacing;
  frame.to_engine = [godot = frame.to_engine, shift_x, shift_z](double x, double y, double h) {
    std::array<double, 3> p = godot(x, y, h);
    p[0] += shift_x;
    p[2] += shift_z;
    return p;
  };
  nlohmann::json sidecar = {
      {"engine", "terrain3d"},
      {"height", height_file},
      {"height_format", exr ? "32-bit float EXR, channel R, metres"
                            : "R16: 16-bit little-endian, row 0 north, min -> 0, max -> 65535"},
      {"control", "control.exr"},
      {"control_format",
       "32-bit float EXR, channel R, holding Terrain3D's uint32 control bits: base texture id "
       "bits 31-27, overlay id 26-22, blend 21-14 (0: all base, 255: all overlay); the rest 0"},
      {"size", {grid.width, grid.height}},
      {"vertex_spacing", spacing},
      {"region_size", region},
      {"regions", {regions_x, regions_z}},
      {"import_position", {import_x, import_z}},
      {"import_position_m", {shift_x, shift_z}},
      {"height_min_m", map.min},
      {"height_max_m", map.max},
      {"height_step_m", map.step()},
      {"world_origin", frame.origin},
      {"crs_wkt", source.set.crs_wkt},
      {"textures", textures},
      {"script", "import_terrain3d.gd"}};
  if (source.input_heights != nullptr) {
    const EngineVertices v =
        engine_vertices(grid, grid.width, grid.height, spacing, OriginCorner::north_west);
    std::vector<std::vector<std::uint8_t>> weights;
    if (source.splat != nullptr) weights = quantize_weights(engine_weights(source, v));
    sidecar["layers"] = write_edit_layers(source, v, weights, v, names, 0.0, dir, stager, result);
  }
  result.files.push_back(dir / "import_terrain3d.gd");
  write_json(result.files.back(), import_script(sidecar), stager);
  result.files.push_back(dir / "terrain3d.json");
  write_json(result.files.back(), sidecar.dump(2) + "\n", stager);
  for (const auto& p : write_splines(source.curves, height_at(source), frame, dir, stager))
    result.files.push_back(p);
  result.settings = {
      fmt::format("terrain3d: {} and control.exr ({} x {}), region size {}, vertex_spacing {}",
                  (dir / height_file).string(), grid.width, grid.height, region, spacing),
      fmt::format("terrain3d: import position ({}, {}) vertices = ({:.3f}, 0, {:.3f}) m", import_x,
                  import_z, shift_x, shift_z),
      fmt::format("terrain3d: heights {:.3f} .. {:.3f} m{}", map.min, map.max,
                  exr ? "" : fmt::format(" (R16 range; {:.5f} m per step)", map.step())),
      fmt::format("terrain3d: run {} in Godot's script editor with the Terrain3D node selected",
                  (dir / "import_terrain3d.gd").string())};
  return result;
}

}  // namespace tw::detail
