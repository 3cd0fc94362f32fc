#!/usr/bin/env bash
# `make cross`: builds the run-time library and the C harness's run-time part for Windows x64 (MinGW-w64)
# and Linux aarch64 (Debian's cross compiler), and runs them with ctest under wine and qemu-user.
# usage: cross.sh BUILD_DIR [JOBS]      (build trees BUILD_DIR/cross-windows, BUILD_DIR/cross-aarch64)
set -euo pipefail
cd "$(dirname "$0")/.."
build="$1"; jobs="${2:-$(nproc)}"
# Wine: its own prefix in the build tree, headless (no $DISPLAY needed), no Mono/Gecko installers, quiet.
export WINEPREFIX="$(mkdir -p "$build" && cd "$build" && pwd)/wineprefix" WINEDEBUG=-all
export WINEDLLOVERRIDES="mscoree=d;mshtml=d;winemenubuilder.exe=d"
unset DISPLAY
status=0
for target in windows aarch64; do
  case "$target" in
    windows) toolchain=cmake/toolchains/mingw-w64-x86_64.cmake ;;
    aarch64) toolchain=cmake/toolchains/aarch64-linux-gnu.cmake ;;
  esac
  dir="$build/cross-$target"
  start=$(date +%s)
  # The DLL and the test executables share one directory, where Windows looks for a DLL first.
  cmake -S . -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DTETPROBE_RUNTIME_ONLY=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_RUNTIME_OUTPUT_DIRECTORY="$(pwd)/$dir/bin" >/dev/null
  cmake --build "$dir" -j "$jobs"
  ctest --test-dir "$dir" --output-on-failure || status=1
  echo "cross $target: $(( $(date +%s) - start )) s"
done
# Let wineserver exit before the build directory may be removed.
command -v wineserver >/dev/null && wineserver -w || true
exit $status
