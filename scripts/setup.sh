#!/usr/bin/env bash
# Installs what stairplan needs from Debian's packages, only what is missing; safe to run again.
set -euo pipefail
packages=(
  build-essential cmake pkg-config ninja-build lld
  libeigen3-dev coinor-libipopt-dev libnlopt-cxx-dev liborocos-kdl-dev liburdfdom-dev
  libfcl-dev libccd-dev catch2 libbenchmark-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libmujoco-dev libqhull-dev
  chromium ffmpeg librsvg2-bin libegl-dev libosmesa6-dev
  coinor-libclp-dev
  libtinyxml2-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
  libopenmpi-dev openmpi-bin
  libassimp-dev
  doxygen
)
# `setup.sh sanitize` (scripts/sanitize.sh, run by scripts/test.sh) also installs the sanitizer
# toolchain: clang 14 with its ASan/UBSan/libFuzzer runtimes.
# Node.js and npm for the viewer's bundle, from Debian unless the machine has them already (a
# Node.js that ships its own npm conflicts with Debian's npm package).
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
if [ "${1:-}" = sanitize ]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
# The browser viewer's three.js (and esbuild, which bundles it into the page at build time), as
# stairplan/viewer/package-lock.json pins them.
viewer="$(cd "$(dirname "$0")/.." && pwd)/stairplan/viewer"
if [ ! -f "$viewer/node_modules/.package-lock.json" ] || [ "$viewer/package-lock.json" -nt "$viewer/node_modules/.package-lock.json" ]; then
  (cd "$viewer" && npm ci --no-audit --no-fund --loglevel=error)
fi
