#!/usr/bin/env bash
# Runs each fuzz target for SECONDS (short in `make test`, long in `make fuzz`) from a seed corpus.
set -uo pipefail
build="$1"; seconds="${2:-20}"; root="$(cd "$(dirname "$0")/../.." && pwd)"
passed=0; failed=0
for target in fuzz_load fuzz_build; do
  corpus="$build/corpus-$target"; mkdir -p "$corpus"
  seeds=()
  if [ "$target" = fuzz_load ] && [ -d "$root/tests/unit/golden" ]; then
    for f in "$root"/tests/unit/golden/*.bin; do
      [ -e "$f" ] || continue
      for m in 0 1; do printf "\\x0$m" | cat - "$f" > "$corpus/seed-$m-$(basename "$f")"; done
    done
  fi
  # Inputs that once failed stay in the corpus, so every run replays them first.
  if [ -d "$root/tests/fuzz/seeds/$target" ]; then cp "$root/tests/fuzz/seeds/$target"/* "$corpus/"; fi
  echo "fuzzing $target for ${seconds}s"
  if "$build/tests/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
       -artifact_prefix="$build/crash-$target-" "$corpus" > "$build/$target.log" 2>&1; then
    grep -E "^(Done|stat::number_of_executed_units)" "$build/$target.log" | head -2
    passed=$((passed+1))
  else
    echo "FAIL: $target"; tail -40 "$build/$target.log"; failed=$((failed+1))
  fi
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
