#!/usr/bin/env bash
# Long fuzzing (issue #28): runs each libFuzzer target of tests/fuzz, built in the sanitized build
# folder (configured as scripts/sanitize.sh configures it), to a number of runs or minutes, whichever
# comes first. Each fuzzer starts from its corpus kept outside the repository, which grows from one
# run to the next, and from tests/fuzz/corpus/<name>; afterwards the inputs that reach new edges are
# minimised back into tests/fuzz/corpus/<name> (libFuzzer -merge=1). Prints per fuzzer the runs,
# the coverage and the findings; exits 1 when there is a finding. CI does not run this: it keeps
# scripts/sanitize.sh's few seconds per fuzzer.
#
# Usage: scripts/fuzz_long.sh [--runs N] [--minutes M] [--no-merge] [fuzzer...]
#   --runs N      stop each fuzzer after N runs (default 10000000)
#   --minutes M   stop each fuzzer after M minutes (default 60)
#   --no-merge    leave tests/fuzz/corpus alone
#   fuzzer...     names as in tests/fuzz/corpus (urdf, qps, ...); default all
# Environment: STAIRPLAN_ASAN_DIR (build folder, default build-asan), STAIRPLAN_FUZZ_WORK (corpora,
# findings and logs; default ~/.cache/stairplan-fuzz), STAIRPLAN_FUZZ_NICE (default 19).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=10000000
minutes=60
merge=1
names=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=${2:?--runs needs a number}; shift 2 ;;
    --minutes) minutes=${2:?--minutes needs a number}; shift 2 ;;
    --no-merge) merge=0; shift ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz_long: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) names+=("$1"); shift ;;
  esac
done
if ! [[ "$runs" =~ ^[0-9]+$ && "$minutes" =~ ^[0-9]+$ ]] || [ "$runs" -eq 0 ] || [ "$minutes" -eq 0 ]; then
  echo "fuzz_long: --runs and --minutes take whole numbers above 0" >&2
  exit 2
fi
if [ ${#names[@]} -eq 0 ]; then
  for dir in tests/fuzz/corpus/*/; do names+=("$(basename "$dir")"); done
fi
for name in "${names[@]}"; do
  if [ ! -d "tests/fuzz/corpus/$name" ]; then
    echo "fuzz_long: no fuzzer '$name' (no tests/fuzz/corpus/$name)" >&2
    exit 2
  fi
done

build=${STAIRPLAN_ASAN_DIR:-build-asan}
work=${STAIRPLAN_FUZZ_WORK:-${XDG_CACHE_HOME:-$HOME/.cache}/stairplan-fuzz}
niceness=${STAIRPLAN_FUZZ_NICE:-19}
stamp=$(date -u +%Y%m%dT%H%M%SZ)
mkdir -p "$work/logs" "$work/findings"

# Only the fuzz targets are built (not the sanitized test suite).
scripts/sanitize_configure.sh "$build"
targets=()
for name in "${names[@]}"; do targets+=(--target "fuzz_$name"); done
nice -n 10 cmake --build "$build" -j 2 "${targets[@]}"
source scripts/sanitizer_env.sh

# The last "key: N" that libFuzzer printed in `log`, or "-".
last_number() { grep -o "$2: *[0-9]*" "$1" | tail -1 | grep -o '[0-9]*$' || echo -; }

summary=()
found=0
for name in "${names[@]}"; do
  corpus="$work/corpus/$name"
  log="$work/logs/$name-$stamp.log"
  mkdir -p "$corpus"
  echo "fuzz_long: fuzz_$name up to $runs runs or $minutes min (corpus $corpus, log $log)"
  t0=$(date +%s)
  status=0
  nice -n "$niceness" "$build/bin/fuzz_$name" -runs="$runs" -max_total_time=$((minutes * 60)) -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/findings/$name-$stamp-" \
    "$corpus" "tests/fuzz/corpus/$name" 2>"$log" || status=$?
  seconds=$(( $(date +%s) - t0 ))
  done_runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$' || true)
  [ -n "$done_runs" ] || done_runs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#' || echo -)
  cov=$(last_number "$log" cov)
  features=$(last_number "$log" ft)
  findings=$(find "$work/findings" -name "$name-$stamp-*" ! -name "*slow-unit-*" | wc -l)
  if [ "$status" -ne 0 ] || [ "$findings" -gt 0 ]; then
    found=1
    [ "$findings" -gt 0 ] || findings=1
    echo "fuzz_long: fuzz_$name stopped with exit $status; reproducers in $work/findings/$name-$stamp-*" >&2
    grep -E 'ERROR|SUMMARY|finding:|==[0-9]+==' "$log" | head -20 >&2 || true
    echo "  Each finding becomes a corpus file and a unit test on the path that failed" >&2
    echo "  (tests/hardening/parser_regression_test.cc, tests/hardening/bad_input_test.cc)." >&2
  fi
  added=0
  if [ "$merge" = 1 ]; then
    before=$(find "tests/fuzz/corpus/$name" -type f | wc -l)
    # Edges only (-use_counters=0): merging on hit-count features too kept three times as many
    # inputs (720 against 233 for plan.json after 2 minutes); the outside corpus keeps those.
    nice -n "$niceness" "$build/bin/fuzz_$name" -merge=1 -use_counters=0 -timeout=10 -rss_limit_mb=2048 \
      "tests/fuzz/corpus/$name" "$corpus" >>"$log" 2>&1 || echo "fuzz_long: merging fuzz_$name's corpus failed (see $log)" >&2
    added=$(( $(find "tests/fuzz/corpus/$name" -type f | wc -l) - before ))
  fi
  summary+=("$(printf '%-14s %10s %8s %7s %8s %8s %10s %9s' "$name" "$done_runs" "$seconds" "$cov" "$features" \
    "$(find "$corpus" -type f | wc -l)" "+$added" "$findings")")
done

echo
printf '%-14s %10s %8s %7s %8s %8s %10s %9s\n' fuzzer runs seconds cov ft corpus "repo corp" findings
printf '%s\n' "${summary[@]}"
echo "fuzz_long: corpora in $work/corpus; tests/fuzz/corpus gained what the merges added (git status shows it)"
exit "$found"
