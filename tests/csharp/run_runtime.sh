#!/usr/bin/env bash
# The C# binding against the run-time library: a store built with the full library, then the binding compiled with
# TETPROBE_RUNTIME (and without TETPROBE_SPAN: the array-only build) loading libtetprobe_runtime.so.
# usage: run_runtime.sh PATH/TO/libtetprobe.so PATH/TO/libtetprobe_runtime.so SCRATCH_DIR   (prints "N passed, N failed")
set -euo pipefail
full="$(readlink -f "$1")"
runtime="$(readlink -f "$2")"
scratch="$3"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
binding="$here/../../bindings/csharp"
mkdir -p "$scratch/full" "$scratch/runtime"
ln -sf "$full" "$scratch/full/libtetprobe.so"
ln -sf "$runtime" "$scratch/runtime/libtetprobe_runtime.so"
sources=("$binding"/*.cs "$here/Tests.cs" "$here/HeaderCheck.cs" "$here/RuntimeTests.cs")
mcs -nologo -warnaserror -define:TETPROBE_RUNTIME_TESTS -target:exe -out:"$scratch/full/Writer.exe" "${sources[@]}"
LD_LIBRARY_PATH="$scratch/full" mono --debug "$scratch/full/Writer.exe" "$scratch/work" "$here/../../capi/tetprobe.h"
mcs -nologo -warnaserror -define:TETPROBE_RUNTIME_TESTS -define:TETPROBE_RUNTIME -target:exe \
    -out:"$scratch/runtime/RuntimeTests.exe" "${sources[@]}"
# Only libtetprobe_runtime.so is on the search path: a call that reached the full library would fail to load.
LD_LIBRARY_PATH="$scratch/runtime" mono --debug "$scratch/runtime/RuntimeTests.exe" "$scratch/work" "$here/../../capi/tetprobe.h"
