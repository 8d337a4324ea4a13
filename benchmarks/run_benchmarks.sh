#!/usr/bin/env bash
# One command for the benchmarks: builds the cpu preset if needed, then reports
# particle-steps per second, the time per phase (phases_ms_share), and
# bytes per particle on 1 and 2 threads; the machine's memory bandwidth (STREAM triad)
# beside them; and the DEM side by side with LAMMPS (Debian's lammps package, installed
# if missing) on the same lattice case, with their ratio from the same run, so that a
# noisy machine cannot fake a gain. Results: benchmarks/results.jsonl
# usage: benchmarks/run_benchmarks.sh [dem]   (dem: only the DEM against LAMMPS)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/cpu/benchmarks/bench_sph ] && [ -x build/cpu/benchmarks/bench_stream ] ||
  { cmake --preset cpu && cmake --build --preset cpu -j"$(nproc)"; }
out=benchmarks/results.jsonl
only=${1:-all} # "dem": only the DEM against LAMMPS (appended to the results)
[ "$only" = dem ] || : > "$out"
if [ "$only" != dem ]; then
# Memory bandwidth, 1 and 2 threads: SPH throughput compares across machines per GB/s.
for threads in 1 2; do build/cpu/benchmarks/bench_stream $threads | tee -a "$out"; done
for threads in 1 2; do
  # 3D dam break with a column, about 1.3e5 fluid particles (dp = 8.5 mm).
  build/cpu/benchmarks/bench_sph cases/bench_dambreak.yaml 40 $threads | tee -a "$out"
  # SPHERIC test 2 at about 1e6 particles (dp = 10.2 mm).
  build/cpu/benchmarks/bench_sph cases/spheric_test2.yaml 10 $threads --set dp=0.0102 | tee -a "$out"
  # The same case at about 1e5 particles, for cost per particle-step against size.
  build/cpu/benchmarks/bench_sph cases/spheric_test2.yaml 40 $threads --set dp=0.0237 | tee -a "$out"
  # DEM: spheres touching on a lattice, settling, full contact model.
  build/cpu/benchmarks/bench_dem 20000 2000 $threads | tee -a "$out"
  build/cpu/benchmarks/bench_dem 100000 2000 $threads | tee -a "$out"
  # Coupled SPH-DEM step against the same water without spheres, 0 to 1e4 spheres.
  for n in 0 100 1000 10000; do build/cpu/benchmarks/bench_coupling $n 20 $threads | tee -a "$out"; done
  # Neighbour search alone, 1e6 particles.
  build/cpu/benchmarks/bench_neighbour 1000000 $threads | tee -a "$out"
done
fi

# DEM against LAMMPS, one thread each, the same lattice case (bench_dem's sizes:
# nx = 2 floor(cbrt(N/2)), ny = nx/2, nz = N / (nx ny)), measured back to back.
if ! command -v lmp >/dev/null 2>&1; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get install -y -qq --no-install-recommends lammps
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Three rows per size: surge's linear spring with shear history only against LAMMPS's
# gran/hooke/history (the same model), surge's full model (rolling, twisting, intact
# bonds) against the same LAMMPS run, Hertz-Mindlin against LAMMPS's granular
# hertz/material with Mindlin tangential stiffness.
for n in 20000 100000; do
 for pair in "hooke hooke" "full hooke" "hertz_mindlin hertz_mindlin"; do
  read -r model lmodel <<<"$pair"
  surge_row=$(build/cpu/benchmarks/bench_dem $n 2000 1 "$model")
  read -r nx ny nz < <(/usr/bin/python3 -c "import math; n=$n; nx=int(math.pow(n/2, 1/3)+1e-9)*2; ny=nx//2; print(nx, ny, n//(nx*ny))")
  OMP_NUM_THREADS=1 lmp -in benchmarks/lammps_dem_lattice.in -var nx "$nx" -var ny "$ny" -var nz "$nz" -var steps 2000 \
    -var model "$lmodel" -log none -screen "$tmp/lmp_$n.txt" >/dev/null
  /usr/bin/python3 - "$surge_row" "$tmp/lmp_$n.txt" "$lmodel" <<'PY' | tee -a "$out"
import json, re, sys
surge = json.loads(sys.argv[1])
loop = [l for l in open(sys.argv[2]) if l.startswith("Loop time")][-1]
t, steps, atoms = re.match(r"Loop time of ([0-9.e+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", loop).groups()
lmp = int(steps) * int(atoms) / float(t)
print(json.dumps({"bench": "dem_vs_lammps", "surge_model": surge["model"], "lammps_model": sys.argv[3],
                  "spheres": surge["spheres"], "lammps_atoms": int(atoms), "threads": 1,
                  "surge_sphere_steps_per_s": surge["sphere_steps_per_s"], "lammps_sphere_steps_per_s": lmp,
                  "surge_over_lammps": surge["sphere_steps_per_s"] / lmp,
                  "surge_contacts_per_sphere": surge["contacts_per_sphere"],
                  "surge_bytes_per_sphere": surge["bytes_per_sphere"]}))
PY
 done
done
