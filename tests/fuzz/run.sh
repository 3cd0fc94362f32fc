#!/usr/bin/env bash
# Runs each fuzz target from the seed corpus.
#   run.sh BUILD short   `make test`: a fixed seed and a fixed number of runs from a fresh corpus, so
#                        every machine explores the same inputs and a failure reproduces.
#   run.sh BUILD SECONDS `make fuzz`: a random seed for SECONDS per target, growing the kept corpus.
set -uo pipefail
build="$1"; mode="${2:-short}"; root="$(cd "$(dirname "$0")/../.." && pwd)"
declare -A short_runs=([fuzz_load]=1000000 [fuzz_build]=8000 [fuzz_bsp]=300000)
passed=0; failed=0
for target in fuzz_load fuzz_build fuzz_bsp; do
  if [ "$mode" = short ]; then
    corpus="$build/corpus-$target-short"; rm -rf "$corpus"
    # No comparison-guided mutations: they feed on compared values, pointers among them, which
    # differ from run to run, and would make the explored inputs differ too.
    limits=(-seed=20261121 -runs="${short_runs[$target]}" -max_total_time=300 -use_cmp=0)
    what="${short_runs[$target]} runs, seed 20261121"
  else
    corpus="$build/corpus-$target"
    limits=(-max_total_time="$mode")
    what="${mode}s"
  fi
  mkdir -p "$corpus"
  if [ "$target" = fuzz_load ] && [ -d "$root/tests/unit/golden" ]; then
    for f in "$root"/tests/unit/golden/*.bin; do
      [ -e "$f" ] || continue
      for m in 0 1; do printf "\\x0$m" | cat - "$f" > "$corpus/seed-$m-$(basename "$f")"; done
    done
  fi
  # Inputs that once failed stay in the corpus, so every run replays them first.
  if [ -d "$root/tests/fuzz/seeds/$target" ]; then cp "$root/tests/fuzz/seeds/$target"/* "$corpus/"; fi
  echo "fuzzing $target: $what"
  # Without address randomisation where setarch allows it, for the same reason.
  launcher=(); if [ "$mode" = short ] && setarch "$(uname -m)" -R true 2>/dev/null; then launcher=(setarch "$(uname -m)" -R); fi
  if "${launcher[@]}" "$build/tests/$target" "${limits[@]}" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
       -artifact_prefix="$build/crash-$target-" "$corpus" > "$build/$target.log" 2>&1; then
    grep -E "^(Done|stat::number_of_executed_units)" "$build/$target.log" | head -2
    passed=$((passed+1))
  else
    echo "FAIL: $target (reproduce: $build/tests/$target $build/crash-$target-*)"; tail -40 "$build/$target.log"
    failed=$((failed+1))
  fi
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
