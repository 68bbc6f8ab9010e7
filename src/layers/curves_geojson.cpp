// The run's centerlines as GeoJSON through OGR, so that `terraweave export` (and QGIS) read
// them from a finished run.
#include <ogrsf_frmts.h>

#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/input_guard.hpp"
#include "layers/detail/gdal_init.hpp"
#include "layers/export.hpp"

namespace tw {

namespace {

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

}  // namespace

void write_curves_geojson(const std::vector<ExportCurve>& curves, const std::string& crs_wkt,
                          const std::filesystem::path& path) {
  detail::ensure_gdal_registered();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GeoJSON");
  if (driver == nullptr) fail("GDAL has no GeoJSON driver (writing {})", path.string());
  std::unique_ptr<GDALDataset, DatasetCloser> ds(
      driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) fail("cannot create {}: {}", path.string(), CPLGetLastErrorMsg());
  OGRSpatialReference srs;
  const bool has_crs = !crs_wkt.empty() && import_crs(srs, crs_wkt);
  char** options = CSLSetNameValue(nullptr, "COORDINATE_PRECISION", "3");
  OGRLayer* layer = ds->CreateLayer("features", has_crs ? &srs : nullptr, wkbLineString, options);
  CSLDestroy(options);
  if (layer == nullptr) fail("cannot create a layer in {}", path.string());
  OGRFieldDefn cls("class", OFTString), kind("kind", OFTString), fid("fid", OFTInteger64),
      width("width", OFTReal);
  layer->CreateField(&cls);
  layer->CreateField(&kind);
  layer->CreateField(&fid);
  layer->CreateField(&width);
  for (const ExportCurve& c : curves) {
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("class", c.feature_class.c_str());
    feature.SetField("kind", c.kind.c_str());
    feature.SetField("fid", GIntBig(c.fid));
    feature.SetField("width", c.width);
    OGRLineString line;
    for (const Vec2& p : c.points) line.addPoint(p.x, p.y);
    feature.SetGeometry(&line);
    if (layer->CreateFeature(&feature) != OGRERR_NONE)
      fail("cannot write feature {} of class {} to {}", c.fid, c.feature_class, path.string());
  }
  ds.reset();
}

std::vector<ExportCurve> read_curves_geojson(const std::filesystem::path& path) {
  detail::ensure_gdal_registered();
  std::unique_ptr<GDALDataset, DatasetCloser> ds(
      GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds)
    fail("{}: not valid GeoJSON ({}); run it again", path.string(),
         single_line(CPLGetLastErrorMsg()));
  if (ds->GetLayerCount() != 1)
    fail("{}: {} layers, the centerlines are one; run it again", path.string(),
         ds->GetLayerCount());
  std::vector<ExportCurve> curves;
  OGRLayer* layer = ds->GetLayer(0);
  for (auto& feature : *layer) {
    ExportCurve& c = curves.emplace_back();
    c.feature_class = feature->GetFieldAsString("class");
    c.kind = feature->GetFieldAsString("kind");
    c.fid = feature->GetFieldAsInteger64("fid");
    c.width = feature->GetFieldAsDouble("width");
    const OGRGeometry* g = feature->GetGeometryRef();
    if (g == nullptr || wkbFlatten(g->getGeometryType()) != wkbLineString)
      fail("{}: feature {} of class {} is not a line string", path.string(), c.fid,
           c.feature_class);
    for (const OGRPoint& p : *g->toLineString()) c.points.push_back({p.getX(), p.getY()});
  }
  return curves;
}

}  // namespace tw
