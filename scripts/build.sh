#!/usr/bin/env bash
# Configures and builds into build/ (Release, warnings as errors); incremental on a second run.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# STAIRPLAN_QUICK_TEST_BUILD=ON|OFF: the test programs as unity sources over one precompiled header
# (a shorter build from scratch, longer incremental ones; kept in build/'s cache once given).
quick=()
[ -z "${STAIRPLAN_QUICK_TEST_BUILD:-}" ] || quick=(-DSTAIRPLAN_QUICK_TEST_BUILD="$STAIRPLAN_QUICK_TEST_BUILD")
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSTAIRPLAN_WERROR=ON "${quick[@]}" >/dev/null
cmake --build build -j "$jobs" "$@"
