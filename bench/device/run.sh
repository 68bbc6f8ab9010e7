#!/usr/bin/env bash
# The DP row benchmark on every OpenCL device of this machine, in one command:
#   bash bench/device/run.sh            (from anywhere; BUILD_DIR=... to choose the build folder)
# Installs what scripts/setup.sh installs (nothing else), builds the two bench targets, lists the
# OpenCL devices with clinfo, then prints ms per DP row for the chain (199x82) and braid (325x64)
# exemplars on the CPU backend and on each OpenCL device, beside the paper's GTX 580 figures
# (Zhou et al. 2013: ~30 ms and ~650 ms per row). Prints numbers; never fails on time.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${BUILD_DIR:-$root/build-device-bench}
jobs=${JOBS:-$(nproc)}

bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTERRAWEAVE_BENCH=ON \
  >/dev/null
cmake --build "$build" -j"$jobs" --target bench_synth_opencl >/dev/null

echo "== OpenCL devices (clinfo -l)"
clinfo -l
devices=$(clinfo -l | grep -c 'Device #' || true)
if [ "$devices" -eq 0 ]; then
  echo "no OpenCL device: only the CPU backend can be measured" >&2
fi
echo "== ms per DP row (find valid + compact + extract + update), paper: GTX 580"
export TERRAWEAVE_KERNEL_DIR="$root/kernels"
for ((i = 0; i < devices; ++i)); do
  echo "-- device $i"
  TERRAWEAVE_OPENCL_DEVICE=$i "$build/bench/bench_synth_opencl" --cases --rows "${ROWS:-6}"
done
