#!/usr/bin/env bash
# Compiles the C# binding and its tests with mcs and runs them with mono against libtetprobe.
# usage: run.sh PATH/TO/libtetprobe.so SCRATCH_DIR      (prints "N passed, N failed")
set -euo pipefail
library="$(readlink -f "$1")"
scratch="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
binding="$here/../../bindings/csharp"
mkdir -p "$scratch"
# DllImport("tetprobe") resolves to libtetprobe.so found through LD_LIBRARY_PATH.
ln -sf "$library" "$scratch/libtetprobe.so"
# Debian's mcs (Mono 6) has Span<T> in its corlib: the span overloads are compiled and tested.
mcs -nologo -warnaserror -define:TETPROBE_SPAN -target:exe -out:"$scratch/TetProbeTests.exe" "$binding"/*.cs \
    "$here/Tests.cs" "$here/HeaderCheck.cs" "$here/SceneTests.cs" "$here/StoreTests.cs" "$here/VersionTests.cs" \
    "$here/PlacementTests.cs"
LD_LIBRARY_PATH="$scratch${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" mono --debug "$scratch/TetProbeTests.exe" "$scratch/work" \
    "$here/../../capi/tetprobe.h" "$here/../../samples/scenes"
