#!/usr/bin/env bash
# Module boundaries (DESIGN.md, "Module boundaries"; docs/methods.md), each include of src/ an
# error when it breaks one:
#   - a module includes another module's detail/ headers (`<module>/.../detail/<header>`);
#   - a file outside src/pipeline includes a method's glue (`pipeline/methods/...`): the
#     commands reach the methods through public pipeline headers (pipeline/area_output.hpp...);
#   - a method's glue includes another method's (`pipeline/methods/<other>/...`): methods read
#     each other's work through the seam only (SynthesisMethod::keep_out).
#   module_boundaries_test.sh SOURCE_DIR
# SOURCE_DIR holds src/; tests/scripts/module_boundaries_selftest.sh runs it on trees that break
# each rule.
set -euo pipefail
cd "$1/src"
status=0
violation() {
  echo "module_boundaries: src/$1:$2 includes $3, $4" >&2
  status=1
}
while IFS=: read -r file line text; do
  included=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"$text")
  module=${file%%/*}
  if [[ $included == */detail/* && ${included%%/*} != "$module" ]]; then
    violation "$file" "$line" "$included" "another module's detail/"
  fi
  if [[ $included == pipeline/methods/* ]]; then
    if [[ $module != pipeline ]]; then
      violation "$file" "$line" "$included" "a method's glue, internal to src/pipeline"
    elif [[ $file == pipeline/methods/* ]]; then
      including_method=$(cut -d/ -f3 <<<"$file")
      included_method=$(cut -d/ -f3 <<<"$included")
      if [[ $including_method != "$included_method" ]]; then
        violation "$file" "$line" "$included" "another method's glue"
      fi
    fi
  fi
done < <(grep -rnE '#include "[^"]*(/detail/|pipeline/methods/)' --include='*.cpp' --include='*.hpp' . |
  sed 's|^\./||')
exit $status
