#!/usr/bin/env bash
# Installs terraweave's Debian dependencies, and the extra packages named as arguments (e.g.
# scripts/fuzz.sh's clang). Idempotent and quiet: does nothing when all packages are already
# installed, so a second run costs a second.
#   bash scripts/setup.sh [PACKAGE...]          what building and testing need (scripts/test.sh)
#   bash scripts/setup.sh --build [PACKAGE...]  what configuring, building and running need
#                                               (scripts/build.sh, scripts/demo.sh): no browser,
#                                               Dask, GDAL/OIIO command-line tools or clinfo
set -euo pipefail

build_only=false
if [ "${1:-}" = "--build" ]; then
  build_only=true
  shift
fi

# python3: cmake/lazy_library_stubs.py writes the stubs that load GDAL on first use.
packages=(
  build-essential cmake ninja-build pkg-config git time python3
  libgdal-dev
  libgeographiclib-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd
  libopenimageio-dev libopenexr-dev
  libgtest-dev libgmock-dev libbenchmark-dev libvalijson-dev
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev libtbb-dev nlohmann-json3-dev
  libeigen3-dev libnanoflann-dev libboost-dev libxxhash-dev libcgal-dev libcpp-httplib-dev
  nodejs
  "$@"
)
# What only the tests, benchmarks and scripts use: the viewer's screenshot tests (chromium; the
# drawing page's driver talks to it with python3-websocket), the Dask driver, GDAL's and OIIO's
# tools, clinfo, and dpkg-shlibdeps for the .deb (CPack).
if ! $build_only; then
  packages+=(gdal-bin python3-gdal clinfo openimageio-tools chromium python3-websocket
    python3-distributed dpkg-dev)
fi

# npm vendors three.js for `terraweave view` at build time. Debian's npm package conflicts with
# a nodejs that bundles its own npm (NodeSource's), so it is installed only where npm is absent.
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
