#!/usr/bin/env bash
# A module never includes another module's detail/ headers (DESIGN.md, "Module boundaries"):
# every `#include "<module>/.../detail/<header>"` in src/<other module>/ is an error, but for the
# includes listed below, which wait for a public home (docs/methods.md, "Homes").
#   module_boundaries_test.sh SOURCE_DIR
set -euo pipefail
cd "$1/src"
# "<including file> <included header's file name>": the area and grow glue that `terraweave area`
# and `terraweave grow` share with the run's methods, until the methods' folders expose it.
allowed="commands/area_command.cpp area_canvas.hpp
commands/area_command.cpp area_lead.hpp
commands/area_command.cpp area_output.hpp
commands/grow_command.cpp grow_region.hpp"
status=0
while IFS=: read -r file line text; do
  included=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"$text")
  [[ ${included%%/*} == "${file%%/*}" ]] && continue  # its own module's
  if ! grep -qxF "$file ${included##*/}" <<<"$allowed"; then
    echo "module_boundaries: src/$file:$line includes $included, another module's detail/" >&2
    status=1
  fi
done < <(grep -rnE '#include "[^"]*/detail/' --include='*.cpp' --include='*.hpp' .  | sed 's|^\./||')
exit $status
