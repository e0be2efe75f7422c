#!/usr/bin/env bash
# Configures and builds into build/ (Release, warnings as errors); incremental on a second run.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSTAIRPLAN_WERROR=ON >/dev/null
cmake --build build -j "$jobs" "$@"
