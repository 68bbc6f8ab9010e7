#pragma once
// What line and polygon ingest share: opening a layer with its filter, the transformation into
// the grid's CRS, the grid's extent as a polygon, and checks on raw coordinates.
#include <ogrsf_frmts.h>

#include <cstdint>
#include <memory>
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

// Moves geometry into the grid's CRS (and checks the result is finite and plausible there);
// tw::Error naming label and fid when PROJ cannot.
void transform_to_grid(OGRGeometry& geometry, const OpenVectorLayer& layer, std::int64_t fid);

// The vertices of a line string, as they are.
std::vector<Vec2> curve_points(const OGRSimpleCurve& curve);

// The vertices of a line string, dropping consecutive duplicates.
std::vector<Vec2> distinct_points(const OGRSimpleCurve& curve);

// Drops Z and M values (heights come from the heightfield); true when there were any.
bool drop_z_and_m(OGRGeometry& geometry);

}  // namespace tw::detail
