#pragma once
// The OpenStreetMap tagging conventions terraweave reads (the table is in docs/osm.md): widths
// from `width`, `lanes` or the road / waterway class, kinds from the selecting key, and
// bridges, tunnels and layers from `bridge`, `tunnel` and `layer`.
#include <optional>
#include <string>
#include <string_view>

#include "geo/structure.hpp"

namespace tw {

// The tags of one way that decide its width (empty = the way has no such tag).
struct OsmWidthTags {
  std::string width;  // metres ("7", "7 m", "7.5m"), per OSM wiki Key:width
  std::string lanes;  // a count of lanes, per OSM wiki Key:lanes
  std::string highway;
  std::string waterway;
  std::string natural;
};

struct OsmWidth {
  std::optional<double> metres;  // none when no tag gives a width
  std::string from;              // what gave it: "width=7 m", "lanes=2", "highway=primary"
  std::string problem;           // a tag that was present but unusable (and why), else empty
};

// Metres of carriageway per lane when a way gives `lanes` but no `width`.
inline constexpr double kOsmLaneWidth = 3.5;

// `width` when it is a positive number of metres, else `lanes` x kOsmLaneWidth, else the
// class default of highway=*, waterway=* or natural=* (docs/osm.md). A width in other units
// (feet, "narrow") or a lane count that is not a positive integer is skipped with a problem.
OsmWidth osm_width(const OsmWidthTags& tags);

// The default width of one class value, e.g. ("highway", "primary") -> 7; none when the table
// has no entry.
std::optional<double> osm_class_width(std::string_view key, std::string_view value);

// The terrain kind a selecting key implies: highway -> "road", waterway -> "river",
// natural -> "ridge"; "" for any other key.
std::string_view osm_kind_of_key(std::string_view key);

// bridge=* other than "no" (and "0", "false") is a bridge; tunnel=* likewise a tunnel, except
// tunnel=building_passage, which runs at ground level through a building. Values are
// case-sensitive, as in OSM.
Structure osm_structure(std::string_view bridge, std::string_view tunnel);

// `layer` as an integer ("-1", "2"); none for an empty or malformed value ("1;2", "high").
std::optional<int> parse_osm_layer(std::string_view layer);

}  // namespace tw
