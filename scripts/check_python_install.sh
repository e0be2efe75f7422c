#!/usr/bin/env bash
# Installs the built project to a temporary prefix and imports the Python package from that
# prefix's site-packages (STAIRPLAN_PYTHON_SITE, relative to the prefix), not from the build tree.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=$(mktemp -d /tmp/stairplan-pyprefix.XXXXXX)
trap 'rm -rf "$prefix"' EXIT
cmake --install "${STAIRPLAN_BUILD_DIR:-build}" --prefix "$prefix" >/dev/null
site="$prefix/${STAIRPLAN_PYTHON_SITE:?the site-packages path relative to the prefix}"
cd "$prefix"
PYTHONPATH="$site" "${STAIRPLAN_PYTHON:-/usr/bin/python3}" -c "
import sys, stairplan
assert stairplan.__file__.startswith(sys.argv[1]), stairplan.__file__
stairs = stairplan.Stairs(rise=0.18)
print('stairplan', stairplan.__version__, 'from', stairplan.__file__, '-', stairs)
" "$site"
