#!/usr/bin/env bash
# Distributed-run scaling on one machine: the SPHERIC case at about 1e6 particles for a
# fixed number of steps as
#   (a) the single-process build, 2 threads            (the reference)
#   (b) the MPI build, 1 process x 2 threads
#   (c) the MPI build, 1 process x 1 thread
#   (d) the MPI build, 2 processes x 1 thread
# and prints particle-steps per second (time loop only), parallel efficiency of (d)
# against (c) and (b), bytes sent per process per step and the share of the loop spent
# in the halo exchange. Results: benchmarks/results_mpi.jsonl.
# usage: benchmarks/mpi_scaling.sh [STEPS] [DP]   (defaults 30, 0.0102 m: 1.04e6 particles)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-30}
dp=${2:-0.0102}
[ -x build/cpu/src/surge/surge ] || { cmake --preset cpu && cmake --build --preset cpu -j"$(nproc)"; }
[ -x build/mpi/src/surge/surge ] || { cmake --preset mpi && cmake --build --preset mpi -j"$(nproc)"; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=""
[ "$(id -u)" -eq 0 ] && root="--allow-run-as-root"
export OMP_WAIT_POLICY=PASSIVE
sets=(--set dp="$dp" --set time.max_steps="$steps" --set time.output_every=100 --set time.gauge_every=100
      --set time.end=100 --quiet)
run() { # label processes threads binary
  local label=$1 np=$2 th=$3 bin=$4
  if [ "$np" = 0 ]; then
    OMP_NUM_THREADS=$th "$bin" run cases/spheric_test2.yaml --out "$work/$label" --threads "$th" "${sets[@]}"
  else
    OMP_NUM_THREADS=$th mpirun --oversubscribe --bind-to none $root -n "$np" "$bin" run cases/spheric_test2.yaml \
      --out "$work/$label" --threads "$th" "${sets[@]}"
  fi
}
run single_2t 0 2 build/cpu/src/surge/surge
run mpi_1x2 1 2 build/mpi/src/surge/surge
run mpi_1x1 1 1 build/mpi/src/surge/surge
run mpi_2x1 2 1 build/mpi/src/surge/surge
/usr/bin/python3 - "$work" "$steps" <<'PY' | tee -a benchmarks/results_mpi.jsonl
import json, sys
work, steps = sys.argv[1], int(sys.argv[2])
s = {k: json.load(open(f"{work}/{k}/summary.json")) for k in ["single_2t", "mpi_1x2", "mpi_1x1", "mpi_2x1"]}
pss = {k: v["particle_steps_per_second"] for k, v in s.items()}
n = s["mpi_1x1"]["particles"]["fluid"] + s["mpi_1x1"]["particles"]["wall"]
d = s["mpi_2x1"]["distributed"]
ex = d["rank0"]
row = {"bench": "mpi_scaling", "case": "spheric_test2", "particles": n, "steps": steps,
       "particle_steps_per_s": pss,
       "efficiency_2x1_vs_1x1": pss["mpi_2x1"] / (2 * pss["mpi_1x1"]),
       "ratio_2x1_vs_1x2": pss["mpi_2x1"] / pss["mpi_1x2"],
       "ratio_mpi_1x2_vs_single_2t": pss["mpi_1x2"] / pss["single_2t"],
       "bytes_sent_per_rank_per_step": ex["bytes_sent_per_exchange"],
       "halo_particles_rank0": ex["halo_particles"],
       "exchange_share_of_loop_rank0": ex["exchange_seconds"] / s["mpi_2x1"]["loop_seconds"],
       "exchange_share_of_loop_1x1": s["mpi_1x1"]["distributed"]["rank0"]["exchange_seconds"] / s["mpi_1x1"]["loop_seconds"],
       "rss_bytes_per_particle": {k: v["bytes_per_particle"] for k, v in s.items()}}
print(json.dumps(row))
PY
