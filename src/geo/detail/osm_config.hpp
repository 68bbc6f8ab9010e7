#pragma once
// terraweave's configuration of GDAL's OSM driver (its osmconf.ini): the tags we read
// become columns (docs/osm.md, "Columns"), the rest stay in other_tags.
#include <string>

namespace tw::detail {

// The path of our osmconf.ini (in GDAL's /vsimem/, written once per process), to pass as
// OSM_CONFIG_FILE while opening a dataset.
const std::string& osm_config_file();

}  // namespace tw::detail
