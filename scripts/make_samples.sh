#!/usr/bin/env bash
# Regenerates the real sample data in samples/ (dem.tif, map.gpkg, dem_wgs84.tif,
# lines_wgs84.geojson, olinda.osm) and the exemplars in samples/exemplars/, plus the previews
# in docs/images/. Not part of the build or CI: run it by hand when the samples change.
#
# Sources, all from Debian packages (installed below, NOT listed in scripts/setup.sh):
#   r-cran-stars  tif/olinda_dem_utm25s.tif   Olinda (Brazil) DEM, 90 m, UTM 25S
#   r-cran-terra  ex/elev.tif                 Luxembourg elevation, 30", EPSG:4326
#   gmt-gshhg     WDBII rivers (via `gmt coast -Ia -M -Df`), the Moselle centreline
# Tools: GDAL/OGR Python bindings, numpy, Pillow (python3-gdal python3-numpy python3-pil).
# Output is deterministic (fixed crops, fixed drawn coordinates, fixed seeds and dates).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=/usr/bin/python3 # Debian's python, where python3-gdal/numpy/pil live

if [[ "${1:-}" == "--install" ]]; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    python3-numpy python3-pil python3-gdal r-cran-stars r-cran-terra gmt gmt-gshhg osmctools
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# WDBII river centrelines (all classes) around the Luxembourg crop, as GMT multi-segment text.
(cd "$work" && gmt coast -R6.0/6.8/49.2/49.9 -Ia -M -Df >wdbii_rivers.txt) # in $work: gmt leaves gmt.history behind

$PY scripts/make_samples.py samples "$work/wdbii_rivers.txt" docs/images
$PY scripts/make_exemplars.py samples/exemplars docs/images
$PY scripts/make_osm_sample.py # samples/olinda.osm, drawn over dem.tif from map.gpkg
