#!/usr/bin/env bash
# MPI scaling of `stairplan sweep`: the same grid on 1 rank and on 2 ranks (cold vs cold: each run
# plans every point from scratch), throughput in points per wall second and the ratio; also the
# CPU seconds per point, which the machine's other load does not change, and the load average, so
# a ratio measured on a busy machine can be read for what it is. Not a test: run it by hand.
#   bash bench/sweep_mpi_scaling.sh [build_dir] [grid N] [steps]     (defaults: build 10 3)
set -euo pipefail
build=${1:-build}
n=${2:-10}
steps=${3:-3}
bin="$build/bin/stairplan"
[ -x "$bin" ] || { echo "no $bin: build the stairplan target first" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "no mpirun: install openmpi-bin (scripts/setup.sh)" >&2; exit 2; }
root=(); [ "$(id -u)" -eq 0 ] && root=(--allow-run-as-root)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
grid=(sweep --rise "0.08:0.25:$n" --run "0.20:0.35:$n" --steps "$steps" --validation-step 0.1)
echo "grid ${n}x${n}, $steps steps; $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
declare -A rate
for ranks in 1 2; do
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$out/cpu$ranks" \
    mpirun "${root[@]}" --oversubscribe -np "$ranks" "$bin" "${grid[@]}" --csv "$out/r$ranks.csv" >"$out/log$ranks" 2>/dev/null
  end=$(date +%s.%N)
  points=$(grep -c '^[0-9]' "$out/r$ranks.csv")
  read -r user sys <"$out/cpu$ranks"
  rate[$ranks]=$(echo "$points / ($end - $start)" | bc -l)
  printf '%d rank(s): %d points in %.1f s wall = %.3f points/s; %.2f CPU s per point; load after: %s\n' \
    "$ranks" "$points" "$(echo "$end - $start" | bc -l)" "${rate[$ranks]}" "$(echo "($user + $sys) / $points" | bc -l)" \
    "$(cut -d' ' -f1-3 /proc/loadavg)"
done
cmp -s <(grep -v '^#' "$out/r1.csv") <(grep -v '^#' "$out/r2.csv") && echo "CSVs identical" || echo "CSVs DIFFER"
printf 'throughput 2 ranks / 1 rank: %.2fx\n' "$(echo "${rate[2]} / ${rate[1]}" | bc -l)"
