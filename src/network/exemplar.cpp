#include "network/exemplar.hpp"

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "core/boost_geometry.hpp"
#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "network/detail/ogr_polygons.hpp"
#include "network/detail/svg_lines.hpp"

namespace tw {

namespace {

using namespace geometry;

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetCloser>;

Dataset open_vector(const std::string& path, const std::string& subject) {
  GDALAllRegister();
  Dataset ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) fail("{} {}: cannot open as vector data: {}", subject, path, CPLGetLastErrorMsg());
  return ds;
}

OGRLayer* layer_of(GDALDataset& ds, const std::string& path, const std::string& layer,
                   const std::string& where, const std::string& subject) {
  OGRLayer* l = layer.empty() ? ds.GetLayer(0) : ds.GetLayerByName(layer.c_str());
  if (!l) fail("{} {}: no layer '{}'", subject, path, layer);
  if (!where.empty() && l->SetAttributeFilter(where.c_str()) != OGRERR_NONE)
    fail("{} {}: bad --where '{}': {}", subject, path, where, CPLGetLastErrorMsg());
  return l;
}

// A metric frame for the layer: its own CRS when projected, else a local azimuthal equidistant
// frame at the centre of its extent (lengths within 0.1 % over a county-sized map).
OGRSpatialReference metric_frame(OGRLayer& layer, const std::string& path,
                                 const std::string& subject) {
  OGRSpatialReference srs;
  if (const OGRSpatialReference* own = layer.GetSpatialRef()) srs = *own;
  if (srs.IsEmpty() || srs.IsProjected()) return srs;
  OGREnvelope e;
  if (layer.GetExtent(&e, TRUE) != OGRERR_NONE)
    fail("{} {}: no extent to place a metric frame", subject, path);
  OGRSpatialReference local;
  local.SetWellKnownGeogCS("WGS84");
  local.SetAE(0.5 * (e.MinY + e.MaxY), 0.5 * (e.MinX + e.MaxX), 0.0, 0.0);
  return local;
}

void add_parts(const OGRGeometry* g, std::int64_t fid, NetworkLines& out) {
  if (!g) return;
  switch (wkbFlatten(g->getGeometryType())) {
    case wkbLineString:
    case wkbLinearRing: {
      const auto* ls = g->toLineString();
      std::vector<Vec2> pts;
      for (int i = 0; i < ls->getNumPoints(); ++i) {
        const Vec2 p{ls->getX(i), ls->getY(i)};
        if (pts.empty() || !(pts.back() == p)) pts.push_back(p);
      }
      if (pts.size() >= 2) {
        out.lines.push_back(std::move(pts));
        out.fids.push_back(fid);
      }
      break;
    }
    case wkbPolygon: {  // a polygon's rings are lines of the network (county boundaries)
      out.from_polygons = true;
      for (const OGRLinearRing* ring : *g->toPolygon()) add_parts(ring, fid, out);
      break;
    }
    case wkbMultiLineString:
    case wkbMultiPolygon:
    case wkbGeometryCollection:
      for (const OGRGeometry* part : *g->toGeometryCollection()) add_parts(part, fid, out);
      break;
    default:
      break;
  }
}

}  // namespace

std::pair<std::string, std::string> split_source(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  const std::size_t slash = text.rfind('/');
  if (colon == std::string::npos || (slash != std::string::npos && colon < slash) ||
      std::filesystem::exists(text))
    return {text, ""};
  return {text.substr(0, colon), text.substr(colon + 1)};
}

std::vector<Polygon> read_region_polygons(const std::string& source, const std::string& where,
                                          const std::string& target_wkt,
                                          const std::string& subject) {
  const auto [path, layer_name] = split_source(source);
  Dataset ds = open_vector(path, subject);
  OGRLayer* layer = layer_of(*ds, path, layer_name, where, subject);
  std::unique_ptr<OGRCoordinateTransformation> transform;
  if (!target_wkt.empty() && layer->GetSpatialRef()) {
    OGRSpatialReference target;
    target.importFromWkt(target_wkt.c_str());
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference own = *layer->GetSpatialRef();
    own.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (!own.IsSame(&target)) transform.reset(OGRCreateCoordinateTransformation(&own, &target));
  }
  std::vector<Polygon> out;
  layer->ResetReading();
  for (auto& f : *layer) {
    OGRGeometry* g = f->GetGeometryRef();
    if (!g) continue;
    std::unique_ptr<OGRGeometry> copy(g->clone());
    if (transform && copy->transform(transform.get()) != OGRERR_NONE)
      fail("{} {}: FID {}: cannot transform into the network's frame", subject, path, f->GetFID());
    const auto add_polygon = [&](const OGRPolygon* p) {
      Polygon polygon;
      for (const OGRLinearRing* ring : *p) {
        Ring r;
        for (int i = 0; i < ring->getNumPoints(); ++i) r.push_back({ring->getX(i), ring->getY(i)});
        if (r.size() > 1 && r.front() == r.back()) r.pop_back();
        polygon.push_back(std::move(r));
      }
      if (p->get_Area() <= 0.0)
        fail("{} {}: FID {}: a degenerate (zero-area) polygon", subject, path, f->GetFID());
      out.push_back(std::move(polygon));
    };
    const auto type = wkbFlatten(copy->getGeometryType());
    if (type == wkbPolygon)
      add_polygon(copy->toPolygon());
    else if (type == wkbMultiPolygon)
      for (const OGRPolygon* p : *copy->toMultiPolygon()) add_polygon(p);
    else
      fail("{} {}: FID {}: not a polygon ({})", subject, path, f->GetFID(),
           copy->getGeometryName());
  }
  if (out.empty()) fail("{} {}: no polygon", subject, path);
  return out;
}

NetworkLines cut_network_lines(const NetworkLines& lines, const std::vector<Polygon>& region) {
  NetworkLines out;
  out.crs_wkt = lines.crs_wkt;
  out.region = region;
  out.from_polygons = lines.from_polygons;
  const std::unique_ptr<OGRGeometry> cut(detail::to_ogr(region).MakeValid());
  for (std::size_t i = 0; i < lines.lines.size(); ++i) {
    OGRLineString ls;
    for (Vec2 p : lines.lines[i]) ls.addPoint(p.x, p.y);
    const std::unique_ptr<OGRGeometry> inside(ls.Intersection(cut.get()));
    add_parts(inside.get(), lines.fids[i], out);
  }
  return out;
}

NetworkLines read_network_lines(const NetworkSource& s, Warnings& warnings) {
  NetworkLines out;
  const auto [path, layer_name] = split_source(s.source);
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  if (extension == ".svg") {
    if (!s.target_crs_wkt.empty())
      fail(
          "{} {}: an SVG drawing has no CRS; cannot place its lines on the heightfield (save "
          "them in a GeoPackage in a CRS)",
          s.subject, s.source);
    for (detail::SvgLine& line : detail::read_svg_lines(path, s.subject)) {
      std::vector<Vec2> pts;
      for (Vec2 p : line.points) pts.push_back({p.x * s.scale, -p.y * s.scale});
      out.lines.push_back(std::move(pts));
      out.fids.push_back(line.element);
    }
    // Cut like any map (a clone's source and target regions), in the SVG's metres (no CRS).
    out.region = s.region.empty() ? s.region_polygons
                                  : read_region_polygons(s.region, "", "", s.subject + " region");
    if (!out.region.empty()) out = cut_network_lines(out, out.region);
  } else {
    Dataset ds = open_vector(path, s.subject);
    OGRLayer* layer = layer_of(*ds, path, layer_name, s.where, s.subject);
    const OGRSpatialReference* own_crs = layer->GetSpatialRef();
    if (!s.target_crs_wkt.empty() && (!own_crs || own_crs->IsEmpty()))
      fail("{} {}: layer has no CRS; cannot place its lines on the heightfield", s.subject, path);
    OGRSpatialReference frame;
    if (s.target_crs_wkt.empty())
      frame = metric_frame(*layer, path, s.subject);
    else if (frame.importFromWkt(s.target_crs_wkt.c_str()) != OGRERR_NONE)
      fail("{} {}: the heightfield's CRS is not one PROJ reads", s.subject, path);
    std::unique_ptr<OGRCoordinateTransformation> transform;
    if (!frame.IsEmpty()) {
      char* wkt = nullptr;
      frame.exportToWkt(&wkt);
      out.crs_wkt = wkt;
      CPLFree(wkt);
      // A geographic layer goes to its metric frame, any layer to a given target CRS.
      if (own_crs && (!own_crs->IsProjected() || !s.target_crs_wkt.empty())) {
        OGRSpatialReference own = *own_crs;
        own.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        frame.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        if (!own.IsSame(&frame)) {
          transform.reset(OGRCreateCoordinateTransformation(&own, &frame));
          if (!transform)
            fail("{} {}: no transformation from the layer's CRS into the lines' frame: {}",
                 s.subject, path, CPLGetLastErrorMsg());
        }
      }
    }
    if (!s.region.empty())
      out.region = read_region_polygons(s.region, "", out.crs_wkt, s.subject + " region");
    else
      out.region = s.region_polygons;
    layer->ResetReading();
    for (auto& f : *layer) {
      OGRGeometry* g = f->GetGeometryRef();
      if (!g) continue;
      std::unique_ptr<OGRGeometry> copy(g->clone());
      if (transform && copy->transform(transform.get()) != OGRERR_NONE)
        fail("{} {}: FID {}: cannot transform into the {} frame", s.subject, path, f->GetFID(),
             s.target_crs_wkt.empty() ? "metric" : "heightfield's");
      add_parts(copy.get(), f->GetFID(), out);  // a polygon's rings become lines, then the cut
    }
    if (!out.region.empty()) out = cut_network_lines(out, out.region);
  }
  for (std::size_t i = 0; i < out.lines.size(); ++i)
    for (Vec2 p : out.lines[i])
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        fail("{} {}: FID {}: a coordinate that is not a finite number", s.subject, s.source,
             out.fids[i]);
  if (out.lines.empty() && s.min_lines > 0)
    fail("{} {}: no lines{}", s.subject, s.source, out.region.empty() ? "" : " inside the region");
  if (out.lines.size() == 1 && s.min_lines > 1)
    fail("{} {}: FID {}: a single line is no network (it needs junctions to learn from)", s.subject,
         s.source, out.fids.front());
  (void)warnings;
  return out;
}

namespace {

using SegmentValue = std::pair<BgSegment, std::pair<int, int>>;  // (line, segment)

}  // namespace

Network build_planar_network(const NetworkLines& in, double snap_m, const std::string& subject,
                             Warnings& warnings) {
  std::vector<std::vector<Vec2>> lines = in.lines;
  std::vector<std::int64_t> fids = in.fids;
  // Exact duplicate features (same points, either direction): dropped.
  {
    std::map<std::vector<std::pair<double, double>>, std::size_t> seen;
    std::vector<char> drop(lines.size(), 0);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      std::vector<std::pair<double, double>> key;
      for (Vec2 p : lines[i]) key.emplace_back(p.x, p.y);
      auto reversed = key;
      std::reverse(reversed.begin(), reversed.end());
      const auto& k = std::min(key, reversed);
      if (!seen.emplace(k, i).second) {
        drop[i] = 1;
        warnings.add("duplicate_line", subject, fids[i], "an exact duplicate line, dropped");
      }
    }
    std::size_t w = 0;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (!drop[i]) {
        if (w != i) lines[w] = std::move(lines[i]), fids[w] = fids[i];
        ++w;
      }
    lines.resize(w), fids.resize(w);
  }
  // Near-junctions: an end within snap_m of another line (not touching it) is moved onto it.
  if (snap_m > 0.0) {
    bgi::rtree<SegmentValue, bgi::quadratic<16>> index;
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (std::size_t k = 0; k + 1 < lines[i].size(); ++k)
        index.insert({BgSegment(to_bg(lines[i][k]), to_bg(lines[i][k + 1])), {int(i), int(k)}});
    std::vector<SegmentValue> hits;
    int snapped = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      for (int end = 0; end < 2; ++end) {
        Vec2& p = end == 0 ? lines[i].front() : lines[i].back();
        const BgBox box({p.x - snap_m, p.y - snap_m}, {p.x + snap_m, p.y + snap_m});
        hits.clear();
        index.query(bgi::intersects(box), std::back_inserter(hits));
        double best = snap_m;
        Vec2 target = p;
        bool touching = false;
        for (const SegmentValue& h : hits) {
          const auto [line, k] = h.second;
          const std::size_t last = lines[std::size_t(line)].size() - 2;
          if (std::size_t(line) == i &&
              ((end == 0 && k == 0) || (end == 1 && std::size_t(k) == last)))
            continue;  // its own end segment
          const Vec2 a{h.first.first.x(), h.first.first.y()},
              b{h.first.second.x(), h.first.second.y()};
          const double d = distance_to_segment(p, a, b);
          if (d == 0.0) touching = true;
          if (d < best) {
            // Prefer the segment's ends (an existing node) when they are within reach.
            const double da = distance(p, a), db = distance(p, b);
            const Vec2 ab = b - a;
            const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
            target = da < snap_m ? a : db < snap_m ? b : a + ab * t;
            best = d;
          }
        }
        if (!touching && best < snap_m) {
          if (best > 1e-3)  // closer than a millimetre: rounding, not a drawing mistake
            warnings.add("snapped_end", subject, fids[i],
                         fmt::format("an end {:.2f} m from another line, snapped onto it", best));
          p = target;
          ++snapped;
        }
      }
    }
    (void)snapped;
  }
  // GEOS noding: the union of the lines splits them where they cross or touch and dissolves
  // overlaps.
  OGRMultiLineString all;
  double length_in = 0.0;
  for (const auto& line : lines) {
    OGRLineString ls;
    for (Vec2 p : line) ls.addPoint(p.x, p.y);
    length_in += ls.get_Length();
    all.addGeometry(&ls);
  }
  OGRPoint anchor(lines.front().front().x, lines.front().front().y);
  std::unique_ptr<OGRGeometry> noded(all.Union(&anchor));
  if (!noded) fail("{}: GEOS could not node the lines: {}", subject, CPLGetLastErrorMsg());
  NetworkLines pieces;
  add_parts(noded.get(), -1, pieces);
  double length_out = 0.0;
  for (const auto& p : pieces.lines) length_out += polyline_length(p);
  // Adjacent polygons share their borders: dissolving those is no repair worth a warning.
  if (!in.from_polygons && length_in - length_out > 1e-6 * std::max(1.0, length_in))
    warnings.add("duplicate_segments", subject, std::nullopt,
                 fmt::format("{:.1f} m of overlapping segments dissolved", length_in - length_out));
  // The graph: nodes at the pieces' ends, then chains through degree-2 nodes merged.
  Network raw;
  std::map<std::pair<double, double>, int> node_of;
  const auto node = [&](Vec2 p) {
    auto [it, added] = node_of.emplace(std::pair{p.x, p.y}, int(raw.nodes.size()));
    if (added) raw.nodes.push_back(p);
    return it->second;
  };
  for (auto& p : pieces.lines) {
    if (polyline_length(p) <= 0.0) continue;
    NetworkEdge e;
    e.from = node(p.front());
    e.to = node(p.back());
    e.points = std::move(p);
    raw.edges.push_back(std::move(e));
  }
  // Feature ids back on the pieces: the input line nearest to each piece's middle.
  {
    bgi::rtree<SegmentValue, bgi::quadratic<16>> index;
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (std::size_t k = 0; k + 1 < lines[i].size(); ++k)
        index.insert({BgSegment(to_bg(lines[i][k]), to_bg(lines[i][k + 1])), {int(i), int(k)}});
    for (NetworkEdge& e : raw.edges) {
      const Vec2 m = 0.5 * (e.points[0] + e.points[1]);
      std::vector<SegmentValue> nearest;
      index.query(bgi::nearest(to_bg(m), 1), std::back_inserter(nearest));
      if (!nearest.empty()) e.fid = fids[std::size_t(nearest.front().second.first)];
    }
  }
  const std::vector<int> degree = raw.degrees();
  std::vector<std::vector<int>> incident(raw.nodes.size());
  for (std::size_t i = 0; i < raw.edges.size(); ++i) {
    incident[std::size_t(raw.edges[i].from)].push_back(int(i));
    incident[std::size_t(raw.edges[i].to)].push_back(int(i));
  }
  Network net;
  std::vector<int> new_id(raw.nodes.size(), -1);
  const auto keep_node = [&](int n) {
    if (new_id[std::size_t(n)] < 0) {
      new_id[std::size_t(n)] = int(net.nodes.size());
      net.nodes.push_back(raw.nodes[std::size_t(n)]);
    }
    return new_id[std::size_t(n)];
  };
  std::vector<char> used(raw.edges.size(), 0);
  const auto walk = [&](int start_node, int first_edge) {
    NetworkEdge out;
    out.fid = raw.edges[std::size_t(first_edge)].fid;
    out.from = keep_node(start_node);
    int at = start_node, edge = first_edge;
    out.points.push_back(raw.nodes[std::size_t(at)]);
    while (true) {
      used[std::size_t(edge)] = 1;
      const NetworkEdge& e = raw.edges[std::size_t(edge)];
      std::vector<Vec2> pts = e.points;
      int next = e.to;
      if (e.from != at) {
        std::reverse(pts.begin(), pts.end());
        next = e.from;
      }
      out.points.insert(out.points.end(), pts.begin() + 1, pts.end());
      at = next;
      if (degree[std::size_t(at)] != 2 || at == start_node) break;
      const auto& inc = incident[std::size_t(at)];
      const int other = inc[0] == edge ? inc[1] : inc[0];
      if (used[std::size_t(other)]) break;
      edge = other;
    }
    out.to = keep_node(at);
    net.edges.push_back(std::move(out));
  };
  for (std::size_t n = 0; n < raw.nodes.size(); ++n)
    if (degree[n] != 2)
      for (int e : incident[n])
        if (!used[std::size_t(e)]) walk(int(n), e);
  for (std::size_t e = 0; e < raw.edges.size(); ++e)  // closed loops of degree-2 nodes
    if (!used[e]) walk(raw.edges[e].from, int(e));
  // Ends on the cutting region's boundary are cuts, not dangling ends.
  net.on_boundary.assign(net.nodes.size(), 0);
  const std::vector<int> final_degree = net.degrees();
  const double eps = 1e-6 * std::max(1.0, snap_m);
  for (std::size_t n = 0; n < net.nodes.size(); ++n) {
    if (final_degree[n] != 1) continue;
    for (const Polygon& polygon : in.region)
      for (const Ring& ring : polygon)
        for (std::size_t k = 0; k < ring.size(); ++k)
          if (distance_to_segment(net.nodes[n], ring[k], ring[(k + 1) % ring.size()]) < eps + 1e-6)
            net.on_boundary[n] = 1;
  }
  return net;
}

}  // namespace tw
