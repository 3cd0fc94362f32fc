#!/usr/bin/env bash
# Installs every Debian package tetprobe's build, tests, benchmark and cross builds need (README.md, "Two
# commands"). Idempotent: does nothing when all are present.
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config
  libtet1.5-dev libeigen3-dev libembree-dev catch2
  nlohmann-json3-dev libassimp-dev libstb-dev
  python3 python3-numpy python3-scipy python3-matplotlib python3-pytest
  python3-pip python3-setuptools python3-wheel python3-venv
  mono-mcs mono-runtime
  clang-14 libclang-rt-14-dev
  libcgal-dev
  gcc-mingw-w64-x86-64 g++-mingw-w64-x86-64 g++-aarch64-linux-gnu wine wine64 qemu-user
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
echo "installing: ${missing[*]}"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
