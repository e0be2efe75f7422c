#!/usr/bin/env bash
# Every test: set up, build everything, run ctest (which also installs to a temporary prefix and
# builds examples/find_package against it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
cd build && ctest --output-on-failure -j "$jobs"
