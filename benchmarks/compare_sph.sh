#!/usr/bin/env bash
# SPH speed of this tree against an older revision, measured side by side: builds
# bench_sph of REV in a git worktree (build/compare-REV), then runs old and new
# alternately ROUNDS times on the same case and thread count, and prints each run and
# the ratio of the medians (timings on a shared machine drift by +-20 %; alternating
# old and new and taking medians keeps the drift out of the ratio).
# REV "." runs this tree's binary on both sides: with --new, the cost of a setting.
# SURGE_BENCH_BUILD names this tree's build (default build/cpu, built if missing).
# usage: benchmarks/compare_sph.sh REV [CASE] [STEPS] [THREADS] [ROUNDS] [--set KEY=VALUE]... [--new KEY=VALUE]...
#   e.g. benchmarks/compare_sph.sh 825d0fd cases/bench_dambreak.yaml 40 2 5 --set sph.boundary=mdbc
#        benchmarks/compare_sph.sh . cases/bench_dambreak.yaml 40 2 5 --new sph.shifting=fickian
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: compare_sph.sh REV [CASE] [STEPS] [THREADS] [ROUNDS]}
case_file=${2:-cases/bench_dambreak.yaml}
steps=${3:-40}
threads=${4:-2}
rounds=${5:-5}
shift $(($# < 5 ? $# : 5))
sets=() new_sets=() # --set KEY=VALUE: both sides; --new KEY=VALUE: the new side only
while [ $# -ge 2 ]; do
  case "$1" in
  --set) sets+=(--set "$2") ;;
  --new) new_sets+=(--set "$2") ;;
  *) echo "compare_sph.sh: expected --set or --new, got $1" >&2 && exit 2 ;;
  esac
  shift 2
done
new_build=${SURGE_BENCH_BUILD:-build/cpu}
old_src=build/compare-src-$rev
old_build=build/compare-$rev
[ "$rev" = . ] && old_build=$new_build
if [ ! -x "$old_build/benchmarks/bench_sph" ] && [ "$rev" != . ]; then
  rm -rf "$old_src"
  git worktree add --detach "$old_src" "$rev" >/dev/null
  cmake -S "$old_src" -B "$old_build" -DCMAKE_BUILD_TYPE=Release -DSURGE_CUDA=OFF >/dev/null
  cmake --build "$old_build" -j"$(nproc)" --target bench_sph >/dev/null
fi
[ -x "$new_build/benchmarks/bench_sph" ] || { cmake --preset cpu >/dev/null && cmake --build --preset cpu -j"$(nproc)" --target bench_sph >/dev/null; }
export OMP_WAIT_POLICY=PASSIVE
results=$(mktemp)
for r in $(seq "$rounds"); do
  for which in old new; do
    bin=$new_build/benchmarks/bench_sph extra=("${new_sets[@]}")
    [ "$which" = old ] && bin=$old_build/benchmarks/bench_sph extra=()
    row=$("$bin" "$case_file" "$steps" "$threads" "${sets[@]}" "${extra[@]}")
    echo "$which $row" | tee -a "$results" | cut -c1-160
  done
done
/usr/bin/python3 - "$results" "$rev" <<'PY'
import json, statistics, sys
old, new = [], []
for line in open(sys.argv[1]):
    which, row = line.split(" ", 1)
    (old if which == "old" else new).append(json.loads(row)["fluid_steps_per_s"])
mo, mn = statistics.median(old), statistics.median(new)
print(json.dumps({"bench": "compare_sph", "old_rev": sys.argv[2], "old_fluid_steps_per_s": mo,
                  "new_fluid_steps_per_s": mn, "speedup": mn / mo, "runs_each": len(old)}))
PY
rm -f "$results"
