#!/usr/bin/env bash
# Installs terraweave into a temporary prefix, moves it elsewhere and runs it from there with an
# empty environment (no TERRAWEAVE_*) and, where user namespaces allow (Debian 12), the source
# and build trees hidden under empty mounts: run (an installed pipeline), synth on the OpenCL
# synthesis), view and export must work from the installed files alone (issue #22 item 2).
#   install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "install_test: FAILED: $*" >&2
  exit 1
}

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || fail "cmake --install"
mkdir "$work/moved"
mv "$work/prefix" "$work/moved/terraweave"
p="$work/moved/terraweave"
for f in bin/terraweave lib/libtw_pipeline.a lib/libtw_core.a include/terraweave/pipeline/run.hpp \
  lib/libtw_commands.a include/terraweave/commands/area_command.hpp \
  lib/cmake/terraweave/terraweaveConfig.cmake lib/cmake/terraweave/terraweaveTargets.cmake \
  lib/pkgconfig/terraweave.pc share/terraweave/kernels/row_update.cl \
  share/terraweave/pipelines/demo.yaml share/terraweave/samples/dem.tif \
  share/terraweave/docs/pipeline.schema.json \
  share/man/man1/terraweave.1 share/bash-completion/completions/terraweave; do
  [ -f "$p/$f" ] || fail "not installed: $f"
done
# No RPATH/RUNPATH into the build tree; the pkg-config file resolves against where it now is.
if readelf -d "$p/bin/terraweave" | grep -E "RPATH|RUNPATH"; then fail "the program has an RPATH"; fi
cflags=$(PKG_CONFIG_PATH="$p/lib/pkgconfig" pkg-config --cflags terraweave)
[[ "$cflags" == *"-I$p/lib/pkgconfig/../../include/terraweave"* ]] || fail "pkg-config: $cflags"
bash -n "$p/share/bash-completion/completions/terraweave" || fail "bash completion"
# The pipelines name their schema as ../docs/pipeline.schema.json: the program's own.
cmp <("$p/bin/terraweave" schema) "$p/share/terraweave/docs/pipeline.schema.json" ||
  fail "the installed schema is not the program's"

# The commands, from the moved prefix only. `hide` runs them with both trees hidden.
cat >"$work/commands.sh" <<'COMMANDS'
set -euo pipefail
p="$1"
cd "$2"
"$p/bin/terraweave" -q run "$p/share/terraweave/pipelines/generated.yaml" --out out --threads 2
test -f out/height.tif
"$p/bin/terraweave" synth --exemplar "$p/share/terraweave/samples/exemplars/road_lanes_240x64.png" \
  --curve line --length 60 --scale 2 --backend opencl -o lanes.png >synth.log
grep -q "backend opencl" synth.log
test -f lanes.png
"$p/bin/terraweave" -q view out
test "$(stat -c %s out/view.html)" -gt 500000  # three.js inside the page
"$p/bin/terraweave" -q export out --to unreal --out out-ue
ls out-ue | grep -q 'height.*\.png'
echo "commands: ok"
COMMANDS
mkdir "$work/run"
clean_env=(env -i PATH=/usr/bin:/bin HOME="$work" LANG=C.UTF-8)
if unshare --user --map-root-user --mount true 2>/dev/null; then
  "${clean_env[@]}" unshare --user --map-root-user --mount bash -c \
    'mount -t tmpfs none "$2" && mount -t tmpfs none "$1" && shift 2 && bash "$@"' \
    hide "$source" "$build" "$work/commands.sh" "$p" "$work/run" || fail "commands, trees hidden"
  echo "install_test: ran with $source and $build hidden"
else
  echo "install_test: no user namespaces here: the trees stay visible (the check below remains)"
  "${clean_env[@]}" bash "$work/commands.sh" "$p" "$work/run" || fail "commands"
fi

# Without the installed kernels, OpenCL fails naming where it looked: never the source tree.
rm -r "$p/share/terraweave/kernels"
if "${clean_env[@]}" "$p/bin/terraweave" synth --exemplar \
  "$p/share/terraweave/samples/exemplars/road_lanes_240x64.png" --curve line --length 60 \
  --scale 2 --backend opencl -o "$work/run/no-kernels.png" >"$work/no-kernels.log" 2>&1; then
  fail "OpenCL ran without kernels"
fi
grep -q "$p/share/terraweave/kernels" "$work/no-kernels.log" ||
  fail "no-kernels message: $(cat "$work/no-kernels.log")"
echo "install_test: ok"
