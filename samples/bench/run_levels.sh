#!/usr/bin/env bash
# The real-level part of `make bench`: sets up the levels (setup_levels.sh: Debian's openarena-081-maps,
# extracted into BUILD/levels/maps) and runs `tetprobe_bench levels run` on LEVELS ("default", "all" or
# names separated by commas), its prepared levels cached in BUILD/levels/cache across runs. When the set-up
# fails, OUT/levels.json says why ("not_run"), so the report names the part as not run. Then
# `tetprobe_bench levels placement` on the same levels (OUT/levels_placement.json: placement against random,
# lattice and all candidates at 50 to 4,000 probes).
# Usage: run_levels.sh BUILD OUT LEVELS
set -uo pipefail
build="$1"; out="$2"; levels="${3:-default}"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
if ! setup=$(bash "$here/setup_levels.sh" "$build/levels/maps" 2>&1); then
  /usr/bin/python3 -c 'import json, sys; json.dump({"not_run": "setup_levels.sh failed: " + sys.argv[1].strip()[-400:]}, open(sys.argv[2], "w"))' \
    "$setup" "$out/levels.json"
  cp "$out/levels.json" "$out/levels_placement.json"
  echo "$setup"
  exit 1
fi
echo "$setup"
"$build/samples/tetprobe_bench" levels run --levels "$levels" --maps "$build/levels/maps" --cache "$build/levels/cache" --out "$out"
status=$?
"$build/samples/tetprobe_bench" levels placement --levels "$levels" --maps "$build/levels/maps" --cache "$build/levels/cache" --out "$out" \
  || status=1
exit $status
