#!/usr/bin/env bash
# Configures and builds into build/ (Release, warnings as errors); incremental on a second run.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# STAIRPLAN_QUICK_TEST_BUILD=ON|OFF: the test programs as unity sources over one precompiled header;
# STAIRPLAN_UNITY_BUILD=ON|OFF: the module libraries and the CLI as unity sources. Each makes a build
# from scratch shorter and incremental ones longer; kept in build/'s cache once given.
quick=()
[ -z "${STAIRPLAN_QUICK_TEST_BUILD:-}" ] || quick+=(-DSTAIRPLAN_QUICK_TEST_BUILD="$STAIRPLAN_QUICK_TEST_BUILD")
[ -z "${STAIRPLAN_UNITY_BUILD:-}" ] || quick+=(-DSTAIRPLAN_UNITY_BUILD="$STAIRPLAN_UNITY_BUILD")
# A new build folder gets Ninja and lld where the machine has them (setup.sh installs both): on two
# cores a build from scratch spends less time waiting on one target's last object and on linking.
# An existing folder keeps the generator it was made with.
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then
  quick+=(-G Ninja)
fi
if command -v ld.lld >/dev/null; then
  quick+=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld)
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSTAIRPLAN_WERROR=ON "${quick[@]}" >/dev/null
cmake --build build -j "$jobs" "$@"
