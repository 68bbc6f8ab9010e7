#pragma once
// What line and polygon ingest share: opening a layer with its filter, the transformation into
// the grid's CRS, the grid's extent as a polygon, and checks on raw coordinates.
#include <ogrsf_frmts.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/vec2.hpp"
#include "geo/detail/gdal_support.hpp"
#include "geo/features.hpp"

namespace tw::detail {

struct OpenVectorLayer {
  GdalDatasetPtr dataset;
  OGRLayer* layer = nullptr;  // owned by dataset
  std::string label;          // "path:layer", for messages and LineFeature::source
  // Null when the layer is already in the grid's CRS.
  std::unique_ptr<OGRCoordinateTransformation> to_grid;
  // The way back (grid -> layer), to find the grid in the layer's CRS; null when to_grid is.
  std::unique_ptr<OGRCoordinateTransformation> to_layer;
  std::optional<GridSpec> grid;  // the grid features are read for
  // grid_box_in_layer_crs per margin: features of one class share a few widths.
  std::map<double, std::optional<OGREnvelope>> grid_boxes;
  bool source_is_geographic = false;
  std::string crs_name;     // the layer's CRS, for messages
  bool is_geojson = false;  // GeoJSON reads a CRS unknown to PROJ as WGS 84
};

// Opens the layer (the first when source.layer is empty) and applies source.where.
// Throws tw::Error for a missing file, an unknown layer, a bad where clause or a missing CRS.
OpenVectorLayer open_vector_layer(const VectorSource& source, const Heightfield& grid_of);
// The same, staying in the layer's own CRS (to_grid is null).
OpenVectorLayer open_vector_layer(const VectorSource& source);

// The feature's geometry with curves (CircularString, CompoundCurve, MultiCurve...) linearized;
// tw::Error naming label and fid when it has none.
std::unique_ptr<OGRGeometry> linear_geometry(const OGRFeature& feature,
                                             const OpenVectorLayer& layer);

// The grid's extent grown by `margin` metres on every side, in the grid's CRS.
OGRPolygon grid_extent_polygon(const GridSpec& grid, double margin = 0.0);

// Every vertex finite and plausible (|lat| <= 90 and |lon| <= 540 for geographic layers,
// |x|, |y| < 1e9 otherwise), else tw::Error naming label and fid. Call it on the geometry as
// read, in the layer's CRS.
void check_coordinates(const OGRGeometry& geometry, const OpenVectorLayer& layer, std::int64_t fid);

// A box in the layer's CRS holding every point that lands within `margin` metres of the grid:
// the grid's extent grown by margin, its edges densified and transformed into the layer's CRS
// (OCTTransformBounds), grown by a tenth of its span for the curvature between the samples.
// In the grid's own CRS, the grown extent itself. nullopt when the grid cannot be placed in the
// layer's CRS (beyond its domain, across the antimeridian): features are then transformed whole.
std::optional<OGREnvelope> grid_box_in_layer_crs(OpenVectorLayer& layer, double margin);

// The box as a polygon, each edge in 64 segments (so that an edge cut along it keeps its shape
// when transformed vertex by vertex).
OGRPolygon densified_box(const OGREnvelope& box);

// Moves each part of `parts` (a collection, in the layer's CRS) into the grid's CRS and checks
// the result is finite and plausible there (else tw::Error naming label and fid); a part PROJ
// cannot transform is dropped with a `dropped_part` warning naming the FID (far from the grid,
// after clipping in the layer's CRS, that is PROJ's domain ending, not the data's fault). False
// when no part is left.
bool transform_parts_to_grid(OGRGeometryCollection& parts, const OpenVectorLayer& layer,
                             std::int64_t fid, const std::string& subject, Warnings& warnings);

// The layer's next feature (null at the end); tw::Error naming the layer when GDAL reports a
// failure while reading it (the driver would stop early and the layer read short, e.g. an OSM
// file its node index cannot hold).
OGRFeatureUniquePtr next_feature(const OpenVectorLayer& layer);

// Why `layer` (its where clause applied) gave no feature on the grid, for an `empty_source`
// warning: "has no rows", "the where clause ... matches none of its N rows", "its N features lie
// off the heightfield"; nullopt when the layer's extent does not meet the grid's box (nothing
// was to be expected from it there).
std::optional<std::string> why_no_features(OpenVectorLayer& layer, const std::string& where);

// The vertices of a line string, as they are.
std::vector<Vec2> curve_points(const OGRSimpleCurve& curve);

// The vertices of a line string, dropping consecutive duplicates.
std::vector<Vec2> distinct_points(const OGRSimpleCurve& curve);

// Drops Z and M values (heights come from the heightfield); true when there were any.
bool drop_z_and_m(OGRGeometry& geometry);

}  // namespace tw::detail
