#!/usr/bin/env bash
# Installs terraweave into a temporary prefix and builds a small program against it with
# find_package(terraweave) (tests/scripts/consumer), and again with pkg-config, then runs both
# on an installed pipeline.
#   find_package_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source/tests/scripts/consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log" || {
  cat "$work/configure.log"
  exit 1
}
cmake --build "$work/build" >"$work/build.log" 2>&1 || {
  tail -n 40 "$work/build.log"
  exit 1
}
env -u TERRAWEAVE_KERNEL_DIR "$work/build/consumer" "$work/prefix/share/terraweave/pipelines/demo.yaml" |
  tee "$work/out.txt"
grep -Eq '^grid [0-9]+ x [0-9]+, [0-9]+ warnings$' "$work/out.txt"
# shellcheck disable=SC2046
c++ -std=c++20 "$source/tests/scripts/consumer/main.cpp" -o "$work/pc-consumer" \
  $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags --libs terraweave)
"$work/pc-consumer" "$work/prefix/share/terraweave/pipelines/demo.yaml" >"$work/pc-out.txt"
cmp "$work/out.txt" "$work/pc-out.txt"
echo "find_package_test: ok"
