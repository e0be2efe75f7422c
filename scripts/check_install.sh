#!/usr/bin/env bash
# Installs the built project to a temporary prefix, builds examples/find_package against it with
# CMake and again with pkg-config's flags alone, and checks the installed headers.
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
# Built with the core and planning components only, the control loop links none of the heavy
# back-ends: the optimisation core needs Eigen alone, the NLP solvers and MuJoCo are components
# of their own.
heavy=$(ldd "$example_build/control_loop" | grep -Ei 'mujoco|ipopt|nlopt' || true)
if [ -n "$heavy" ]; then
  echo "check_install: the control loop built from core and planning links:" >&2
  echo "$heavy" >&2
  exit 1
fi
"$example_build/control_loop" >/dev/null
echo "control loop from core and planning ran; ldd shows no MuJoCo, Ipopt or NLopt"

# No header of the implementation is installed: every header ours that an installed header
# includes is installed as well (the internal ones are listed in cmake/Install.cmake).
include_root="$prefix/include"
missing=0
while IFS= read -r header; do
  while IFS= read -r included; do
    if [ ! -f "$include_root/$included" ]; then
      echo "check_install: ${header#"$include_root"/} includes \"$included\", which is not installed" >&2
      missing=1
    fi
  done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$header")
done < <(find "$include_root" -name '*.h')
for internal in stairplan/body_nlp/body_nlp_internal.h stairplan/kinematics/urdf_parse.h stairplan/perception/lzf.h; do
  if [ -e "$include_root/$internal" ]; then
    echo "check_install: the internal header $internal is installed" >&2
    missing=1
  fi
done
[ "$missing" = 0 ]
echo "installed headers: $(find "$include_root" -name '*.h' | wc -l), none internal, none including an uninstalled one"

# pkg-config alone, from the install prefix (stairplan.pc finds the prefix from its own place).
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
flags=$(pkg-config --cflags --libs stairplan)
echo "pkg-config stairplan $(pkg-config --modversion stairplan): $flags"
if [[ " $flags " == *" -std="* ]]; then
  echo "check_install: pkg-config's flags choose a language standard, overriding the consumer's" >&2
  exit 1
fi
${CXX:-c++} -std=c++17 -O1 examples/find_package/stair_summary.cc $flags -o "$example_build/stair_summary_pc"
"$example_build/stair_summary_pc" "$prefix/share/stairplan/robots/stairbot.urdf"
echo "the same example built with pkg-config's flags alone and ran"
