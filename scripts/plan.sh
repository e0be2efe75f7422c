#!/usr/bin/env bash
# The main job: set up, build, and plan the default stairs with the built-in robot.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh --target stairplan
build/bin/stairplan plan --out stairplan-out "$@"
