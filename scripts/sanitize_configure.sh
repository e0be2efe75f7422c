#!/usr/bin/env bash
# Configures the sanitized build folder (default build-asan): clang++-14 with AddressSanitizer,
# UndefinedBehaviorSanitizer and the libFuzzer targets (tests/fuzz). One definition for the two
# scripts that use it: scripts/sanitize.sh (CI's sanitized suite and short fuzz run) and
# scripts/fuzz_long.sh (long fuzzing runs).
# Usage: scripts/sanitize_configure.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: scripts/sanitize_configure.sh BUILD_DIR}
scripts/setup.sh sanitize
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$cxx" ]; then
  echo "sanitize: clang++ not found (scripts/setup.sh sanitize installs clang-14 and libclang-rt-14-dev)" >&2
  exit 1
fi
# CI builds this from scratch, so the first build's length is what counts: Ninja and lld, the
# module libraries and the CLI as unity sources (STAIRPLAN_UNITY_BUILD), and the test programs as
# unity sources over one precompiled header (STAIRPLAN_QUICK_TEST_BUILD).
generator=()
if command -v ninja >/dev/null; then
  generator=(-G Ninja)
  # A build folder made earlier with another generator cannot be reconfigured: start it afresh.
  if [ -f "$build/CMakeCache.txt" ] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$build/CMakeCache.txt"; then
    rm -rf "$build"
  fi
fi
linker=()
if command -v ld.lld >/dev/null || command -v ld.lld-14 >/dev/null; then
  linker=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld)
fi
# -O1 keeps the sanitized tests fast enough; line tables are enough for symbolized reports.
# Benchmarks and examples are left out (no sanitized test runs them); warnings are errors only in
# the normal (gcc) build.
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" "${linker[@]}" \
  -DSTAIRPLAN_SANITIZE=ON -DSTAIRPLAN_FUZZ=ON -DSTAIRPLAN_QUICK_TEST_BUILD=ON -DSTAIRPLAN_UNITY_BUILD=ON \
  -DSTAIRPLAN_BUILD_BENCH=OFF -DSTAIRPLAN_BUILD_EXAMPLES=OFF -DSTAIRPLAN_WERROR=OFF >/dev/null
