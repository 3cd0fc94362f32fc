#!/usr/bin/env bash
# Checks the shared libraries' surface: only tp_* symbols are exported, and the run-time library
# depends on neither TetGen nor Embree (a game ships it without the baker).
set -euo pipefail
full="$1"; runtime="$2"; fails=0
for lib in "$full" "$runtime"; do
  bad=$(nm -D --defined-only "$lib" | awk '$2 ~ /[TDBRW]/ {print $3}' | grep -v '^tp_' || true)
  if [ -n "$bad" ]; then echo "FAIL: $lib exports non-tp_ symbols:"; echo "$bad" | head; fails=$((fails+1)); fi
  n=$(nm -D --defined-only "$lib" | awk '$2 ~ /T/ {print $3}' | grep -c '^tp_' || true)
  [ "$n" -ge 20 ] || { echo "FAIL: $lib exports only $n tp_ functions"; fails=$((fails+1)); }
done
if readelf -d "$runtime" | grep -Eq 'NEEDED.*(libtet|embree)'; then
  echo "FAIL: $runtime depends on TetGen or Embree"; fails=$((fails+1))
fi
readelf -d "$full" | grep -q 'NEEDED.*libtet' || { echo "FAIL: $full does not link TetGen"; fails=$((fails+1)); }
echo "$((fails == 0 ? 1 : 0)) passed, $fails failed"
[ "$fails" -eq 0 ]
