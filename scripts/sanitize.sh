#!/usr/bin/env bash
# Hardening run (issue #9): builds the whole test suite with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-asan, runs ctest there, then runs every libFuzzer target
# (tests/fuzz) for a few seconds on its seed corpus. Any sanitizer report or fuzzer finding fails it.
# Environment: STAIRPLAN_ASAN_DIR (build dir, default build-asan), STAIRPLAN_FUZZ_SECONDS (default 5).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${STAIRPLAN_ASAN_DIR:-build-asan}
fuzz_seconds=${STAIRPLAN_FUZZ_SECONDS:-5}
jobs=$(nproc 2>/dev/null || echo 2)
[ "$jobs" -le 2 ] || jobs=2
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$cxx" ]; then
  echo "sanitize: clang++ not found (scripts/setup.sh installs clang-14 and libclang-rt-14-dev)" >&2
  exit 1
fi
start=$(date +%s)
# -O1 keeps the sanitized tests fast enough; line tables are enough for symbolized reports.
# Benchmarks are left out (they are not tests); warnings are errors only in the normal (gcc) build.
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DSTAIRPLAN_SANITIZE=ON -DSTAIRPLAN_FUZZ=ON -DSTAIRPLAN_BUILD_BENCH=OFF -DSTAIRPLAN_WERROR=OFF >/dev/null
cmake --build "$build" -j "$jobs"
echo "sanitize: build took $(( $(date +%s) - start )) s"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Left out of the sanitized run, for these reasons only (the normal build runs them all):
#  - install.find_package_example: installs the instrumented libraries and builds an uninstrumented
#    example against them with the default compiler; a packaging test, not a runtime one.
#  - speed: under ASan these take 50-600 s each on 2 cores (measured 2026-11-22; the first timed out
#    at 600 s), which would take the sanitized run past CI's budget. None had a finding.
#  - "NLopt's SLSQP solves the same horizon NLP": it requires a body-planner Update to finish inside
#    the 2.5 ms wall-clock cycle budget first, which ASan's slowdown breaks (status stale); a timing
#    property, not a memory or UB one.
exclude='^install\.find_package_example$'
exclude+='|^every knot of the body plan passes IK, joint limits and clearance'
exclude+='|^on the flight the body pitches with the s'
exclude+='|^1,000 Update cycles after warm-up allocate nothing'
exclude+='|^the NLP refinement of a whole plan'
exclude+='|^NLopt.s SLSQP solves the same horizon NLP'
exclude+='|^ANYmal C climbs low stairs'
exclude+='|^1000 random code-range staircases'
exclude+='|^sweep CSV is identical for 1 and 2 threads'
exclude+='|^sweep shards merged equal the unsharded sweep'
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
