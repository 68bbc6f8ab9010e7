#pragma once
// `terraweave view RUN_DIR` (docs/cli.md): one self-contained HTML page that shows a run in 3D
// (three.js, inlined at build time): a downsampled height mesh, the splat colours as its
// texture, the avoidance map and the feature lines, each with a toggle. No network needed.
#include <filesystem>
#include <string>

#include "network/growth.hpp"
#include "pipeline/lead.hpp"
#include "pipeline/lead_direction.hpp"

namespace tw {

struct ViewOptions {
  std::filesystem::path run_dir;
  std::filesystem::path out;  // "" = <run_dir>/view.html
  int mesh_size = 256;        // most vertices along the longer side
  int texture_size = 1024;    // most texels along the longer side
  bool verify = true;         // check the run's files against report.json (--no-verify: false)
};

// Reads the height, splat and avoidance layers (GeoTIFFs, or a tiled run's VRT mosaics: see
// pipeline/run_layers.hpp), features.geojson and report.json (only what the page shows,
// downsampled by GDAL on reading) and writes the page atomically; returns its path.
// Throws tw::Error naming a missing file, or (verify) one that no longer matches report.json
// (pipeline/run_layers.hpp, verify_run_files).
std::filesystem::path write_view(const ViewOptions& options);

// The drawing page that `view --serve --exemplar` serves (docs/networks.md, "Drawing"): the run's
// colours as a 2D map in its grid's coordinates, its feature lines, and `save_path` named in the
// page. Throws like write_view.
std::string network_page(const ViewOptions& options, const std::string& save_path);

// The cells the run's avoidance layer forbids (> 0.5), on the run's grid (at most 4096 cells a
// side, coarser for a larger run): what the drawing page's suggestions stay off (its roads,
// rivers, fold-overs...).
ForbiddenMask run_forbidden_mask(const std::filesystem::path& run_dir);

// The run's CRS as WKT (report.json's grid), "" when it has none.
std::string run_crs_wkt(const std::filesystem::path& run_dir);

// A lead's direction over `region` (its largest polygon) on a run, as a network class's `lead:`
// reads it in a pipeline: `contours` over the run's height layer, `nearest_road` along the run's
// `kind: road` features (features.geojson); their fall-back to the long axis as lead_angle has it.
LeadAngle run_lead_angle(const std::filesystem::path& run_dir, Lead lead, double bearing_deg,
                         const std::vector<Polygon>& region);

}  // namespace tw
