#!/usr/bin/env bash
# Installs the built tree into a temporary prefix and builds a tiny C consumer against it twice: with
# find_package(tetprobe) and with pkg-config; runs each against the full and the run-time library, as built
# (no LD_LIBRARY_PATH: pkg-config's --libs carries an RPATH for a prefix outside the system's folders). Runs the
# installed command-line tool from the prefix.
# usage: run.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR      (prints "N passed, N failed")
set -euo pipefail
build="$1"; source="$2"; scratch="$3"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
golden="$source/tests/unit/golden/tiny_store_v6.bin"
rm -rf "$scratch"; mkdir -p "$scratch"
prefix="$scratch/prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
passed=0; failed=0
check() { # name, command...
  local name="$1"; shift
  if out=$("$@" 2>&1); then passed=$((passed+1)); else failed=$((failed+1)); echo "FAIL $name:"; echo "$out" | tail -20; fi
}
# The installed tree: header, versioned libraries with their SONAME links, package and pkg-config files.
libdir=$(dirname "$(find "$prefix" -name 'libtetprobe_runtime.so' | head -1)")
check "header installed" test -f "$prefix/include/tetprobe/tetprobe.h"
check "SONAME" bash -c "readelf -d '$libdir/libtetprobe.so' | grep -q 'SONAME.*libtetprobe.so.[0-9]'"
check "config version file" test -f "$libdir/cmake/tetprobe/tetprobeConfigVersion.cmake"

# The command-line tool, in bin/, finds the installed library by its RPATH ($ORIGIN-relative: the prefix may move).
check "tool installed" test -x "$prefix/bin/tetprobe"
check "tool RUNPATH" bash -c "readelf -d '$prefix/bin/tetprobe' | grep -E 'R(UN)?PATH' | grep -q '\\\$ORIGIN/../lib'"
check "tool version" bash -c "env -u LD_LIBRARY_PATH '$prefix/bin/tetprobe' version | grep -qx 'tetprobe [0-9.]*'"
check "tool uses the installed library" bash -c "found=\$(env -u LD_LIBRARY_PATH ldd '$prefix/bin/tetprobe' | awk '/libtetprobe\\.so/ {print \$3}'); \
  test \"\$(readlink -f \"\$found\")\" = \"\$(readlink -f '$libdir/libtetprobe.so')\""
check "tool info" bash -c "env -u LD_LIBRARY_PATH '$prefix/bin/tetprobe' info '$golden' --json | grep -q '\"probes\": '"
mv "$prefix" "$scratch/moved"
check "tool after moving the prefix" bash -c "env -u LD_LIBRARY_PATH '$scratch/moved/bin/tetprobe' version"
mv "$scratch/moved" "$prefix"

# find_package, from a build directory outside the repository's.
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$build/CMakeCache.txt")
check "find_package configure" cmake -S "$here" -B "$scratch/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release -DTETPROBE_EXPECTED_VERSION="$version"
check "find_package build" cmake --build "$scratch/cmake-build"
check "find_package full" "$scratch/cmake-build/consumer_full" "$golden" full
check "find_package runtime" "$scratch/cmake-build/consumer_runtime" "$golden" runtime
# A version the installed package does not satisfy is refused.
mkdir -p "$scratch/too-new"
printf 'cmake_minimum_required(VERSION 3.18)\nproject(p LANGUAGES C)\nfind_package(tetprobe 99.0 REQUIRED)\n' > "$scratch/too-new/CMakeLists.txt"
check "find_package refuses 99.0" bash -c "! cmake -S '$scratch/too-new' -B '$scratch/too-new/build' -DCMAKE_PREFIX_PATH='$prefix' >/dev/null 2>&1"

# pkg-config, with a plain compiler call; the programs run as built, without LD_LIBRARY_PATH.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
for lib in tetprobe tetprobe_runtime; do
  flavour=full; [ "$lib" = tetprobe_runtime ] && flavour=runtime
  check "pkg-config $lib rpath" bash -c "pkg-config --libs $lib | grep -q -- '-Wl,-rpath,$libdir/pkgconfig/../../lib '"
  check "pkg-config $lib build" bash -c "cc -std=c99 -pedantic -Werror -o '$scratch/pc_$lib' '$here/consumer.c' \$(pkg-config --cflags --libs $lib) -lm"
  check "pkg-config $lib run" env -u LD_LIBRARY_PATH "$scratch/pc_$lib" "$golden" "$flavour"
done
# A system prefix gets no RPATH (the loader searches it anyway); staged with DESTDIR, as a package build would.
rm -rf "$scratch/stage"
DESTDIR="$scratch/stage" cmake --install "$build" --prefix /usr >/dev/null
system_pc=$(find "$scratch/stage" -name tetprobe.pc | head -1)
check "system prefix: no rpath" bash -c "test -n '$system_pc' && grep -q '^Libs: -L\${libdir} -ltetprobe$' '$system_pc'"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
