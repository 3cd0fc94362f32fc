#!/usr/bin/env bash
# The layers' include rules: core/ (the run time) includes nothing from bake/ or capi/, and bake/
# includes nothing from capi/ (the C ABI translates its structs into bake/'s types, never the reverse).
# usage: check_layering.sh SOURCE_DIR
set -euo pipefail
root="$1"; fails=0; checked=0
# layer -> the folders it must not include from
check() {
  local layer="$1"; shift
  local files; files=$(find "$root/$layer" -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' -o -name '*.inl' \) | sort)
  [ -n "$files" ] || { echo "FAIL: no sources under $root/$layer"; fails=$((fails+1)); return; }
  checked=$((checked + $(echo "$files" | wc -l)))
  for banned in "$@"; do
    # #include "capi/x.h", <capi/x.h>, "../capi/x.h", "../../capi/x.h"
    local hits; hits=$(echo "$files" | xargs grep -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]([^\">]*/)?$banned/" || true)
    if [ -n "$hits" ]; then
      echo "FAIL: $layer/ includes $banned/:"; echo "$hits" | sed "s|$root/||"; fails=$((fails+1))
    fi
  done
}
check core bake capi
check bake capi
echo "checked $checked files"
echo "$((fails == 0 ? 3 : 3 - fails)) passed, $fails failed"
[ "$fails" -eq 0 ]
