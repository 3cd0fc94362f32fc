#!/usr/bin/env bash
# Every function declared in the public header is called somewhere in the C harness, so a new tp_
# function cannot be forgotten. usage: check_coverage.sh capi/tetprobe.h tests/c
set -euo pipefail
header="$1"; harness="$2"
functions=$(grep -oE '^TP_API[^(]*\btp_[a-z0-9_]+\(' "$header" | sed -E 's/.*\b(tp_[a-z0-9_]+)\($/\1/' | sort -u)
missing=()
for f in $functions; do
  grep -qE "\\b$f\\(" "$harness"/*.c || missing+=("$f")
done
total=$(echo "$functions" | wc -w)
if [ ${#missing[@]} -gt 0 ]; then
  echo "FAIL: called by no file of $harness: ${missing[*]}"
  echo "$((total - ${#missing[@]})) passed, ${#missing[@]} failed"
  exit 1
fi
echo "$total passed, 0 failed"
