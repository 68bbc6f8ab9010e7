// The field lists of the types a WorldPlan holds (plan_codec.hpp); a method's own types have
// theirs in its file. A field added to one of these types must be added to its list too: the
// plan round-trip test renders from a loaded plan and compares the bytes, so a missing field
// that matters shows there.
#include "pipeline/detail/plan_codec.hpp"

#include "pipeline/detail/plan_binary.hpp"
#include "pipeline/detail/plan_fields.hpp"

namespace tw::detail {

// One definition for both directions: Io is JsonWriter or JsonReader.
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD

TW_FIELDS(GridSpec, F(width) F(height) F(origin_x) F(origin_y) F(pixel_width) F(pixel_height))
TW_FIELDS(Window, F(col0) F(row0) F(width) F(height))
TW_FIELDS(Vec2, F(x) F(y))
TW_FIELDS(TileSpec, F(index) F(ix) F(iy) F(window) F(halo_window))
TW_FIELDS(LineFeature, F(fid) F(points) F(closed) F(width) F(source) F(structure) F(layer))
TW_FIELDS(Curve, F(points) F(closed))
TW_FIELDS(Piece, F(top_left) F(bottom_left) F(bottom_right) F(top_right) F(x0) F(x1))
TW_FIELDS(Ribbon, F(centerline) F(width) F(delta) F(closed) F(pieces))
TW_FIELDS(RoadProfile,
          F(max_grade) F(shoulder_width) F(falloff) F(smoothing) F(max_cut) F(max_fill))
TW_FIELDS(RiverProfile, F(depth) F(bank_width) F(falloff) F(min_slope) F(max_carve))
TW_FIELDS(RidgeProfile, F(height) F(falloff) F(sharpness))
TW_FIELDS(TerrainFeature, F(kind) F(fid) F(subject) F(centerline) F(width) F(structure) F(layer)
                              F(road) F(river) F(ridge))
TW_FIELDS(TerrainParams, F(precedence))
TW_FIELDS(ProfileLimit, F(length) F(excess) F(along) F(at))
TW_FIELDS(FeatureEarthwork, F(max_cut) F(max_fill) F(cut_limited) F(fill_limited))
TW_FIELDS(TerrainPlan, F(features) F(profiles) F(steps) F(input_index) F(earthwork) F(params))
TW_FIELDS(GeneratedTerrain, F(width) F(height) F(pixel_size) F(seed) F(relief) F(crs) F(origin_x)
                                F(origin_y) F(feature_size))
TW_FIELDS(HeightfieldOptions, F(resolution) F(resampling) F(crs))
TW_FIELDS(HeightfieldFile, F(path) F(xxh3_128) F(bytes) F(options))
TW_FIELDS(RenderOptions, F(avoidance_max_distance))
TW_FIELDS(WindowIndex, F(bin_size) F(bins_x) F(bins_y) F(windows) F(offsets) F(items))
TW_FIELDS(Warning, F(code) F(subject) F(fid) F(message))
TW_FIELDS(StageTiming, F(stage) F(seconds))
TW_FIELDS(CacheStatus, F(reused) F(why) F(key))
TW_FIELDS(FeatureReport, F(fid) F(length_m) F(width_m) F(pieces) F(structure) F(layer) F(deck_m)
                             F(moved_max_m) F(moved_mean_m) F(cut_max_m) F(fill_max_m) F(grade_max))
TW_FIELDS(FeatureClassReport, F(name) F(kind) F(source) F(delta_m) F(features) F(ingest_seconds))
// The methods' parts (RunReport::method_parts) are theirs to store (plan_io: encode_report).
TW_FIELDS(RunReport, F(grid) F(crs_wkt) F(heightfield) F(seed) F(stages) F(classes)
                         F(forbidden_pixels) F(total_seconds) F(warnings))

// Avoidance inputs that a plan holds own their geometry: ribbons of synthesized features are
// the plan's own (`patterns`), so pointers into them are never stored.
template <class Io>
static void existing_fields(Io& io, AvoidanceInputs& v) {
  io("polygons", v.polygons);
  io("lines", v.lines);
  io("line_widths", v.line_widths);
  io("include_foldovers", v.include_foldovers);
  io("junction_discs", v.junction_discs);
}
void fields(JsonWriter& io, AvoidanceInputs& v) {
  if (!v.ribbons.empty() || v.current) fail("plan: existing features refer to ribbons");
  existing_fields(io, v);
}
void fields(JsonReader& io, AvoidanceInputs& v) {
  existing_fields(io, v);
}
void fields(BinaryWriter& io, AvoidanceInputs& v) {
  if (!v.ribbons.empty() || v.current) fail("plan: existing features refer to ribbons");
  existing_fields(io, v);
}
void fields(BinaryReader& io, AvoidanceInputs& v) {
  existing_fields(io, v);
}

#undef F
#undef TW_FIELDS

}  // namespace tw::detail
