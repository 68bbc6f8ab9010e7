#!/usr/bin/env bash
# The DP row benchmark on every OpenCL device of this machine, in one command:
#   bash bench/device/run.sh            (from anywhere; BUILD_DIR=... to choose the build folder)
# Installs what scripts/setup.sh installs (nothing else), builds the two bench targets, lists the
# OpenCL devices with clinfo, then prints ms per DP row for the chain (199x82) and braid (325x64)
# exemplars on the CPU backend and on each OpenCL device, beside the paper's GTX 580 figures
# (Zhou et al. 2013: ~30 ms and ~650 ms per row). Prints numbers; never fails on time.
# On a machine with no network and none of our dependencies (a GPU host with only its driver):
# `bash bench/device/bundle.sh DIR` here, then `BUNDLE=DIR bash bench/device/run.sh` there; the
# driver's OpenCL library (libnvidia-opencl, or an ICD file in /etc/OpenCL/vendors) is found there.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${BUILD_DIR:-$root/build-device-bench}
jobs=${JOBS:-$(nproc)}

if [ -n "${BUNDLE:-}" ]; then
  bundle=$(realpath "$BUNDLE")
  vendors=$(mktemp -d)
  cp /etc/OpenCL/vendors/*.icd "$vendors/" 2>/dev/null || true
  driver_dirs=""
  for dir in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu /usr/lib64; do
    if [ -e "$dir/libnvidia-opencl.so.1" ]; then
      echo "$dir/libnvidia-opencl.so.1" >"$vendors/nvidia-$(echo "$dir" | tr / _).icd"
      driver_dirs+=":$dir"
      break
    fi
  done
  export OCL_ICD_VENDORS=$vendors TERRAWEAVE_KERNEL_DIR=$bundle/kernels
  # The carried glibc loader runs both programs on their carried libraries; the driver's folder
  # comes after them (the NVIDIA OpenCL library loads its own helpers from there).
  run_carried() { "$bundle/lib/ld-linux-x86-64.so.2" --library-path "$bundle/lib$driver_dirs" "$@"; }
  clinfo_list() { run_carried "$bundle/clinfo" -l; }
  bench() { run_carried "$bundle/bench_synth_opencl" "$@" --texels "$bundle/texels"; }
else
  bash "$root/scripts/setup.sh"
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTERRAWEAVE_BENCH=ON \
    >/dev/null
  cmake --build "$build" -j"$jobs" --target bench_synth_opencl >/dev/null
  export TERRAWEAVE_KERNEL_DIR="$root/kernels"
  clinfo_list() { clinfo -l; }
  bench() { "$build/bench/bench_synth_opencl" "$@"; }
fi

echo "== OpenCL devices (clinfo -l)"
clinfo_list
devices=$(clinfo_list | grep -c 'Device #' || true)
if [ "$devices" -eq 0 ]; then
  echo "no OpenCL device: only the CPU backend can be measured" >&2
fi
echo "== ms per DP row (find valid + compact + extract + update), paper: GTX 580"
for ((i = 0; i < devices; ++i)); do
  echo "-- device $i"
  TERRAWEAVE_OPENCL_DEVICE=$i bench --cases --rows "${ROWS:-6}"
done
