#!/usr/bin/env bash
# Makes the .deb with CPack (docs/install.md) and checks it: its dependencies come from
# dpkg-shlibdeps (GDAL, OpenImageIO, the OpenCL loader ...), apt can install it here
# (simulated: the test installs nothing), and the program unpacked from it runs from anywhere.
#   deb_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "deb_test: FAILED: $*" >&2
  exit 1
}
(cd "$build" && cpack -G DEB -B "$work/package" >"$work/cpack.log" 2>&1) || {
  cat "$work/cpack.log"
  fail "cpack"
}
deb=$(ls "$work"/package/terraweave_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for library in libgdal libopenimageio libopenexr libyaml-cpp libtbb libxxhash ocl-icd-libopencl1; do
  [[ "$depends" == *"$library"* ]] || fail "no $library in Depends"
done
apt-get install -s "$deb" >"$work/apt.log" 2>&1 || {
  cat "$work/apt.log"
  fail "apt-get install -s"
}
grep -q "^Inst terraweave" "$work/apt.log" || fail "apt would not install it: $(cat "$work/apt.log")"
dpkg-deb -x "$deb" "$work/root"
root="$work/root/usr"
for f in bin/terraweave share/terraweave/kernels/row_update.cl share/man/man1/terraweave.1 \
  lib/cmake/terraweave/terraweaveConfig.cmake lib/pkgconfig/terraweave.pc; do
  [ -f "$root/$f" ] || fail "not in the package: /usr/$f"
done
cd "$work"
env -i PATH=/usr/bin:/bin HOME="$work" "$root/bin/terraweave" synth \
  --exemplar "$root/share/terraweave/samples/exemplars/road_lanes_240x64.png" --curve line \
  --length 60 --scale 2 --backend opencl -o lanes.png >synth.log 2>&1 || fail "$(cat synth.log)"
grep -q "backend opencl" synth.log || fail "$(cat synth.log)"
echo "deb_test: ok"
