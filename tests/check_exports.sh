#!/usr/bin/env bash
# Checks the shared libraries' surface: only tp_* symbols are exported, and the run-time library
# depends on neither TetGen nor Embree (a game ships it without the baker). A Windows DLL (cross build)
# exports only tp_* too and imports only system DLLs (one file to ship, no MinGW runtime beside it).
# usage: check_exports.sh FULL_LIBRARY|- RUNTIME_LIBRARY      ("-": the full library is not built)
set -euo pipefail
full="$1"; runtime="$2"; fails=0
exports() { # library -> one exported symbol per line
  case "$1" in
    *.dll) x86_64-w64-mingw32-objdump -p "$1" | sed -n '/\[Ordinal\/Name Pointer\] Table/,/^$/p' |
             awk 'NR > 1 && NF >= 2 {print $NF}' ;;
    *) nm -D --defined-only "$1" | awk '$2 ~ /[TDBRW]/ {print $3}' ;;
  esac
}
libraries=("$runtime"); [ "$full" != "-" ] && libraries+=("$full")
for lib in "${libraries[@]}"; do
  names=$(exports "$lib")
  bad=$(echo "$names" | grep -v '^tp_' || true)
  if [ -n "$bad" ]; then echo "FAIL: $lib exports non-tp_ symbols:"; echo "$bad" | head; fails=$((fails+1)); fi
  n=$(echo "$names" | grep -c '^tp_' || true)
  [ "$n" -ge 20 ] || { echo "FAIL: $lib exports only $n tp_ functions"; fails=$((fails+1)); }
done
case "$runtime" in
  *.dll)
    imports=$(x86_64-w64-mingw32-objdump -p "$runtime" | awk '/DLL Name:/ {print $3}' | grep -viE '^(kernel32|msvcrt|advapi32|user32)\.dll$' || true)
    [ -z "$imports" ] || { echo "FAIL: $runtime needs DLLs a player does not have: $imports"; fails=$((fails+1)); } ;;
  *)
    if readelf -d "$runtime" | grep -Eq 'NEEDED.*(libtet|embree)'; then
      echo "FAIL: $runtime depends on TetGen or Embree"; fails=$((fails+1))
    fi ;;
esac
if [ "$full" != "-" ]; then
  readelf -d "$full" | grep -q 'NEEDED.*libtet' || { echo "FAIL: $full does not link TetGen"; fails=$((fails+1)); }
fi
echo "$((fails == 0 ? 1 : 0)) passed, $fails failed"
[ "$fails" -eq 0 ]
