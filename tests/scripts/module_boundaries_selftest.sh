#!/usr/bin/env bash
# The boundary check fails on each rule it enforces, naming the file and the line, and passes
# on a tree that keeps them: a few files written into temporary trees.
#   module_boundaries_selftest.sh CHECK_SCRIPT
set -euo pipefail
check=$1
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
failures=0

# A tree holding the allowed includes plus FILE with the line INCLUDE.
tree() {
  local dir=$root/$1
  mkdir -p "$dir/src/pipeline/methods/areas" "$dir/src/pipeline/methods/patterns" \
    "$dir/src/pipeline/detail" "$dir/src/commands" "$dir/src/geo/detail"
  printf '#include "pipeline/methods/areas/areas.hpp"\n#include "pipeline/detail/x.hpp"\n' \
    >"$dir/src/pipeline/methods/areas/area_method.cpp"
  printf '#include "pipeline/methods/patterns/patterns.hpp"\n' >"$dir/src/pipeline/plan.cpp"
  printf '#include "pipeline/area_output.hpp"\n#include "geo/features.hpp"\n' \
    >"$dir/src/commands/area_command.cpp"
  if [[ -n ${2:-} ]]; then
    mkdir -p "$(dirname "$dir/src/$2")"
    printf '// a line\n#include "%s"\n' "$3" >>"$dir/src/$2"
  fi
  echo "$dir"
}

# CASE: the check on a tree with FILE including INCLUDE fails with a message naming FILE:2.
expect_failure() {
  local dir out
  dir=$(tree "$1" "$2" "$3")
  if out=$(bash "$check" "$dir" 2>&1); then
    echo "FAIL $1: the check passed" >&2
    failures=$((failures + 1))
  elif ! grep -qF "src/$2:2 includes $3, $4" <<<"$out"; then
    echo "FAIL $1: expected 'src/$2:2 includes $3, $4', got: $out" >&2
    failures=$((failures + 1))
  fi
}

if ! out=$(bash "$check" "$(tree clean)" 2>&1); then
  echo "FAIL clean: the check failed on a tree that keeps every rule: $out" >&2
  failures=$((failures + 1))
fi
expect_failure detail commands/x.cpp geo/detail/clip.hpp "another module's detail/"
expect_failure pipeline_detail commands/export_command.cpp pipeline/detail/ingest.hpp \
  "another module's detail/"
expect_failure command_method commands/grow_command.cpp pipeline/methods/grown/grow_region.hpp \
  "a method's glue, internal to src/pipeline"
expect_failure other_module geo/y.hpp pipeline/methods/areas/areas.hpp \
  "a method's glue, internal to src/pipeline"
expect_failure method_method pipeline/methods/areas/areas.hpp \
  pipeline/methods/patterns/pattern_method.hpp "another method's glue"
exit $((failures > 0))
