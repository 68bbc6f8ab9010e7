#include "geo/detail/osm_config.hpp"

#include <cpl_vsi.h>

#include <mutex>
#include <string_view>

#include "core/error.hpp"

namespace tw::detail {
namespace {

// GDAL's default osmconf.ini, reduced to what terraweave reads. Every layer reports the tags
// of docs/osm.md as columns, so selections (`tags`, `where`) and the width table work
// on them; closed ways are areas only for the keys that describe areas (a closed
// highway=residential loop stays a line).
constexpr std::string_view kOsmConf =
    R"(closed_ways_are_polygons=aeroway,amenity,boundary,building,craft,geological,historic,landuse,leisure,military,office,place,shop,sport,tourism,water,wetland,natural=wood,natural=water,natural=scrub,natural=grassland,natural=heath,natural=sand,natural=bare_rock,natural=scree,natural=beach,natural=glacier,natural=wetland,highway=platform,public_transport=platform
[points]
osm_id=yes
attributes=name,highway,natural,waterway
ignore=created_by,converted_by,source,time,note,todo,fixme,FIXME
[lines]
osm_id=yes
attributes=name,highway,waterway,natural,railway,bridge,tunnel,layer,width,lanes,surface
ignore=created_by,converted_by,source,time,note,todo,fixme,FIXME
[multipolygons]
osm_id=yes
attributes=name,type,landuse,natural,leisure,building,water,waterway,amenity,layer
ignore=area,created_by,converted_by,source,time,note,todo,fixme,FIXME
[multilinestrings]
osm_id=yes
attributes=name,type,waterway,highway
ignore=area,created_by,converted_by,source,time,note,todo,fixme,FIXME
[other_relations]
osm_id=yes
attributes=name,type
ignore=area,created_by,converted_by,source,time,note,todo,fixme,FIXME
)";

}  // namespace

const std::string& osm_config_file() {
  static const std::string path = "/vsimem/terraweave/osmconf.ini";
  static std::once_flag written;
  std::call_once(written, [] {
    VSILFILE* file = VSIFileFromMemBuffer(
        path.c_str(), reinterpret_cast<GByte*>(const_cast<char*>(kOsmConf.data())),
        vsi_l_offset(kOsmConf.size()), /*bTakeOwnership=*/FALSE);
    if (!file) fail("cannot write GDAL's in-memory {}", path);
    VSIFCloseL(file);
  });
  return path;
}

}  // namespace tw::detail
