#!/usr/bin/env bash
# Packs the DP row benchmark for a machine that has a GPU and its driver but none of our
# dependencies and no network (the device hosts of docs/performance.md's GPU figures):
#   bash bench/device/bundle.sh [DIR]      (default DIR: .device-bundle in the source tree,
#                                          git-ignored; BUILD_DIR=... to choose the build folder)
# DIR gets bench_synth_opencl and clinfo, every shared library they load here (glibc and its
# loader too, so the host's own glibc version does not matter), the OpenCL ICD loader, the two
# exemplars' cost texels (no image library needed there) and the kernels. There:
#   BUNDLE=DIR bash bench/device/run.sh
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${BUILD_DIR:-$root/build-device-bench}
out=$(realpath -m "${1:-$root/.device-bundle}")

bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTERRAWEAVE_BENCH=ON \
  >/dev/null
cmake --build "$build" --target bench_synth_opencl terraweave_image >/dev/null

rm -rf "$out" && mkdir -p "$out/lib"
program=$build/bench/bench_synth_opencl
cp "$program" "$(command -v clinfo)" "$out/"
# Every library either program loads, and the loader that ld.so names in the programs.
for binary in "$program" "$(command -v clinfo)"; do
  ldd "$binary" | awk '/=> \//{print $3} /^\t\/.*ld-linux/{print $1}'
done | sort -u | while read -r lib; do cp -L "$lib" "$out/lib/"; done
# The texels of samples/exemplars/, decoded here where the image module is.
TERRAWEAVE_IMAGE_MODULE=$build/src/libterraweave_image.so "$program" --save-texels "$out/texels"
cp -r "$root/kernels" "$out/kernels"
echo "bundle: $out ($(du -sh "$out" | cut -f1), $(ls "$out/lib" | wc -l) libraries)"
