#!/usr/bin/env bash
# Installs the built project to a temporary prefix and builds examples/find_package against it.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=$(mktemp -d /tmp/stairplan-prefix.XXXXXX)
example_build=$(mktemp -d /tmp/stairplan-example.XXXXXX)
trap 'rm -rf "$prefix" "$example_build"' EXIT
cmake --install "${STAIRPLAN_BUILD_DIR:-build}" --prefix "$prefix" >/dev/null
cmake -S examples/find_package -B "$example_build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$example_build" -j 2 >/dev/null
"$example_build/stair_summary" "$prefix/share/stairplan/robots/stairbot.urdf"
echo "find_package example built and ran against the install prefix"
