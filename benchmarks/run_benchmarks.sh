#!/usr/bin/env bash
# One command for the benchmarks: builds the cpu preset if needed, then reports
# particle-steps per second, the time per phase (phases_ms_share), and
# bytes per particle on 1 and 2 threads. Results: benchmarks/results.jsonl
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/cpu/benchmarks/bench_sph ] || { cmake --preset cpu && cmake --build --preset cpu -j"$(nproc)"; }
out=benchmarks/results.jsonl
: > "$out"
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
