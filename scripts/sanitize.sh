#!/usr/bin/env bash
# Hardening run (issue #9), the second half of scripts/test.sh: builds the whole test suite with
# clang, AddressSanitizer and UndefinedBehaviorSanitizer into build-asan, runs ctest there, then runs
# every libFuzzer target (tests/fuzz) for a few seconds on its seed corpus. Any sanitizer report or
# fuzzer finding fails it.
# Environment: STAIRPLAN_ASAN_DIR (build dir, default build-asan), STAIRPLAN_FUZZ_SECONDS (default 5).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${STAIRPLAN_ASAN_DIR:-build-asan}
fuzz_seconds=${STAIRPLAN_FUZZ_SECONDS:-5}
jobs=$(nproc 2>/dev/null || echo 2)
[ "$jobs" -le 2 ] || jobs=2
start=$(date +%s)
scripts/sanitize_configure.sh "$build"
cmake --build "$build" -j "$jobs"
echo "sanitize: build took $(( $(date +%s) - start )) s"

source scripts/sanitizer_env.sh
# Every test runs (those that take minutes under the sanitizers on fewer samples or shorter
# flights, tests/sanitized.h; a few whole runs whose code a smaller sanitized case runs return early
# there, each naming that case: grep kSanitized tests) but one: install.find_package_example
# installs the instrumented libraries and builds an uninstrumented example against them with the
# default compiler; a packaging test, not a runtime one, and the normal build runs it.
exclude='^install\.find_package_example$'
t0=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j "$jobs" -E "$exclude"
echo "sanitize: ctest took $(( $(date +%s) - t0 )) s"

# Each fuzzer briefly on its seed corpus, as many at once as there are build jobs (a fuzzer uses one
# core); new inputs go to a scratch folder, never into tests/.
scratch=$(mktemp -d /tmp/stairplan-fuzz.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
fuzz() {
  local name=$1 corpus=$2
  "$build/bin/fuzz_$name" -max_total_time="$fuzz_seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$scratch/$name-" "$scratch/$name" "$corpus" 2>"$scratch/$name.log"
}
names=()
pids=()
finish() {  # waits for the running fuzzers; the first that found something fails the run
  local i
  for i in "${!pids[@]}"; do
    if ! wait "${pids[$i]}"; then
      cat "$scratch/${names[$i]}.log" >&2
      echo "sanitize: fuzz_${names[$i]} found a problem (reproducer above)" >&2
      exit 1
    fi
    grep -E '^stat::number_of_executed_units' "$scratch/${names[$i]}.log" || true
  done
  names=()
  pids=()
}
for corpus in tests/fuzz/corpus/*/; do
  name=$(basename "$corpus")
  if [ ! -x "$build/bin/fuzz_$name" ]; then
    echo "sanitize: fuzz_$name was not built" >&2
    exit 1
  fi
  mkdir -p "$scratch/$name"
  echo "sanitize: fuzz_$name for ${fuzz_seconds} s"
  fuzz "$name" "$corpus" &
  names+=("$name")
  pids+=($!)
  [ "${#pids[@]}" -lt "$jobs" ] || finish
done
finish
echo "sanitize: all done in $(( $(date +%s) - start )) s"
