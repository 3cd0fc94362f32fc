#!/usr/bin/env bash
# Compiles the C# binding with samples/unity against the UnityEngine/UnityEditor stand-ins in unity_stubs/ (as Unity
# would: UNITY_5_3_OR_NEWER, UNITY_EDITOR) and runs the conversion and sample tests with mono against libtetprobe.
# usage: run_unity.sh PATH/TO/libtetprobe.so SCRATCH_DIR      (prints "N passed, N failed")
set -euo pipefail
library="$(readlink -f "$1")"
scratch="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$here/../.."
mkdir -p "$scratch"
ln -sf "$library" "$scratch/libtetprobe.so"
# -unsafe only for the stubs' SphericalHarmonicsL2 indexer; the binding and the samples need none.
mcs -nologo -warnaserror -unsafe -define:UNITY_5_3_OR_NEWER -define:UNITY_EDITOR -define:TETPROBE_SPAN -target:exe \
    -out:"$scratch/TetProbeUnityTests.exe" "$root"/bindings/csharp/*.cs "$root"/samples/unity/*.cs \
    "$root"/samples/unity/Editor/*.cs "$here"/unity_stubs/*.cs "$here/UnityTests.cs"
LD_LIBRARY_PATH="$scratch${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" mono --debug "$scratch/TetProbeUnityTests.exe" "$scratch/work"

# The plugin name per target, each variant compiled as Unity would (players without UNITY_EDITOR, so without the
# editor script): the editor always loads the full library.
names=0
check_name() {  # expected-name defines...
    local expected="$1"; shift
    local defines=()
    for d in "$@"; do defines+=("-define:$d"); done
    mcs -nologo -warnaserror -unsafe "${defines[@]}" -target:exe -out:"$scratch/LibraryName.exe" "$root"/bindings/csharp/*.cs \
        "$root"/samples/unity/*.cs "$root"/samples/unity/Editor/*.cs "$here"/unity_stubs/*.cs "$here/LibraryName.cs"
    mono "$scratch/LibraryName.exe" "$expected" || names=1
}
check_name tetprobe UNITY_5_3_OR_NEWER
check_name tetprobe_runtime UNITY_5_3_OR_NEWER TETPROBE_RUNTIME
check_name tetprobe UNITY_5_3_OR_NEWER UNITY_EDITOR TETPROBE_RUNTIME
check_name __Internal UNITY_5_3_OR_NEWER UNITY_IOS TETPROBE_RUNTIME
check_name tetprobe UNITY_5_3_OR_NEWER UNITY_IOS UNITY_EDITOR
check_name tetprobe UNITY_5_3_OR_NEWER UNITY_2021_2_OR_NEWER  # spans on by themselves
exit $names
