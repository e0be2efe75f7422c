#!/usr/bin/env bash
# Hardening run (issue #9), the second half of scripts/test.sh: builds the whole test suite with
# clang, AddressSanitizer and UndefinedBehaviorSanitizer into build-asan, runs ctest there, then runs
# every libFuzzer target (tests/fuzz) for a few seconds on its seed corpus. Any sanitizer report or
# fuzzer finding fails it.
# Environment: STAIRPLAN_ASAN_DIR (build dir, default build-asan), STAIRPLAN_FUZZ_SECONDS (default 5).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh sanitize
build=${STAIRPLAN_ASAN_DIR:-build-asan}
fuzz_seconds=${STAIRPLAN_FUZZ_SECONDS:-5}
jobs=$(nproc 2>/dev/null || echo 2)
[ "$jobs" -le 2 ] || jobs=2
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$cxx" ]; then
  echo "sanitize: clang++ not found (scripts/setup.sh sanitize installs clang-14 and libclang-rt-14-dev)" >&2
  exit 1
fi
# CI builds this from scratch, so the first build's length is what counts: Ninja and lld, and the
# test programs as unity sources over one precompiled header (STAIRPLAN_QUICK_TEST_BUILD).
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
start=$(date +%s)
# -O1 keeps the sanitized tests fast enough; line tables are enough for symbolized reports.
# Benchmarks are left out (they are not tests); warnings are errors only in the normal (gcc) build.
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" "${linker[@]}" \
  -DSTAIRPLAN_SANITIZE=ON -DSTAIRPLAN_FUZZ=ON -DSTAIRPLAN_QUICK_TEST_BUILD=ON \
  -DSTAIRPLAN_BUILD_BENCH=OFF -DSTAIRPLAN_WERROR=OFF >/dev/null
cmake --build "$build" -j "$jobs"
echo "sanitize: build took $(( $(date +%s) - start )) s"

# The end-to-end test programs append detect_stack_use_after_return=0 (cmake/Sanitizers.cmake).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Every test runs (those that take minutes under the sanitizers on fewer samples, tests/sanitized.h)
# but one: install.find_package_example installs the instrumented libraries and builds an
# uninstrumented example against them with the default compiler; a packaging test, not a runtime
# one, and the normal build runs it.
exclude='^install\.find_package_example$'
t0=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j "$jobs" -E "$exclude"
echo "sanitize: ctest took $(( $(date +%s) - t0 )) s"

# Each fuzzer briefly on its seed corpus; new inputs go to a scratch folder, never into tests/.
scratch=$(mktemp -d /tmp/stairplan-fuzz.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
for corpus in tests/fuzz/corpus/*/; do
  name=$(basename "$corpus")
  bin="$build/bin/fuzz_$name"
  if [ ! -x "$bin" ]; then
    echo "sanitize: fuzz_$name was not built" >&2
    exit 1
  fi
  mkdir -p "$scratch/$name"
  echo "sanitize: fuzz_$name for ${fuzz_seconds} s"
  "$bin" -max_total_time="$fuzz_seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$scratch/$name-" "$scratch/$name" "$corpus" 2>"$scratch/$name.log" || {
    cat "$scratch/$name.log" >&2
    echo "sanitize: fuzz_$name found a problem (reproducer above)" >&2
    exit 1
  }
  grep -E '^stat::number_of_executed_units' "$scratch/$name.log" || true
done
echo "sanitize: all done in $(( $(date +%s) - start )) s"
