#!/usr/bin/env bash
# The prepared device check (README.md, section "GPUs"), in two halves:
#
#   scripts/gpu_check.sh build   here, without a GPU: builds the cuda preset (sm_90, or
#                                GPU_CHECK_ARCH), records CPU reference gauges, and puts
#                                everything that must travel into gpu_bundle/ (git-ignored,
#                                < 64 MiB)
#   scripts/gpu_check.sh run     on the GPU machine (carry gpu_bundle): unit tests,
#                                benchmarks, CPU-vs-GPU gauges and validation runs, each
#                                time-boxed, inside 9 minutes; $OUT/summary.md and the
#                                logs in $OUT/gpu_check.tar.gz
#
# `run` needs only the bundle, python3 with numpy, and the NVIDIA driver.
# Rehearsal without a GPU: GPU_CHECK_PRESET=cpu-ci scripts/gpu_check.sh build packs the
# CPU build instead (nothing is compiled for CUDA), and `run` then exercises the script.
set -euo pipefail
cd "$(dirname "$0")/.."
bundle=${GPU_CHECK_BUNDLE:-gpu_bundle}
# The demo's first 100 steps, gauges every 0.2 ms, the height gauge in the column and the
# pressure probe at its foot (the defaults stay dry that early).
demo_sets="--set time.max_steps=100 --set time.gauge_every=0.0002 --set time.output_every=1 \
  --set gauges.0.x=0.07 --set gauges.1.at=[0.02,0.05,0.02]"

build() {
  local preset=${GPU_CHECK_PRESET:-cuda}
  if [ "$preset" = cuda ]; then
    cmake --preset cuda -DCMAKE_CUDA_ARCHITECTURES="${GPU_CHECK_ARCH:-90}"
    cmake --build --preset cuda -j"$(nproc)"
  fi
  # CPU reference for the gauge comparison.
  local cpu=build/cpu-ci/src/surge/surge
  [ -x "$cpu" ] || { cpu=build/cpu/src/surge/surge && cmake --preset cpu && cmake --build --preset cpu -j"$(nproc)"; }
  rm -rf "$bundle" && mkdir -p "$bundle"/{bin,lib,ref}
  local b=build/$preset
  cp "$b"/src/surge/surge "$b"/benchmarks/bench_* "$bundle"/bin/
  find "$b"/tests -maxdepth 1 -name 'test_*' -type f -executable -exec cp {} "$bundle"/bin/ \;
  strip "$bundle"/bin/*
  cp -L /usr/lib/x86_64-linux-gnu/libyaml-cpp.so.0.7 "$bundle"/lib/
  [ "$preset" = cuda ] && cp -L "$(dirname "$(readlink -f "$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)")")"/../lib64/libcudart.so.13 \
    "$bundle"/lib/
  cp -r cases "$bundle"/cases
  mkdir -p "$bundle"/scripts && cp scripts/gpu_check.sh scripts/compare_gauges.py "$bundle"/scripts/
  OMP_WAIT_POLICY=PASSIVE "$cpu" run cases/demo_dambreak.yaml --out "$bundle"/ref/demo --threads 2 \
    --quiet $demo_sets
  du -sh "$bundle"
}

run() {
  local here out t0
  here=$(pwd)
  # Results gather outside $OUT (the copy back takes at most 8 files); the tar and the
  # summary go there at the end.
  local dest=${OUT:-/tmp/out}
  out=$(mktemp -d)/gpu_check
  mkdir -p "$out" "$dest"
  export LD_LIBRARY_PATH=$here/lib:${LD_LIBRARY_PATH:-}
  export PATH=$here/bin:$PATH
  export SURGE_CASES_DIR=$here/cases # test_case_reader's shipped cases, wherever the copy lies
  t0=$(date +%s)
  local summary=$out/summary.md
  {
    echo "# surge device check, $(date -u +%F' '%T) UTC"
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null || true
    echo
    echo "| step | result | seconds |"
    echo "|---|---|---|"
  } >"$summary"
  # step NAME LIMIT_S CMD...: runs CMD with a time box, logs to $out/NAME.log, adds a row.
  # Nothing new starts once the whole check has used its budget (default 500 s, so that
  # the tar and the copy back fit in the device call's 9 minutes). GPU_CHECK_ONLY, a
  # regular expression, runs only the steps whose names match (a second call reruns what
  # failed). A failing step is rerun once under compute-sanitizer (first error only,
  # 60 s), narrowed to the failing or crashing test for the GoogleTest binaries.
  local budget=${GPU_CHECK_BUDGET_S:-500} only=${GPU_CHECK_ONLY:-.} sanitised=0
  step() {
    local name=$1 limit=$2
    shift 2
    [[ $name =~ $only ]] || return 0
    local s rc=0
    s=$(date +%s)
    if ((s - t0 >= budget)); then
      echo "| $name | SKIPPED (budget of $budget s spent) | 0 |" >>"$summary"
      return
    fi
    ((s - t0 + limit > budget)) && limit=$((budget - (s - t0)))
    timeout -s INT -k 10 "$limit" "$@" >"$out/$name.log" 2>&1 || rc=$?
    local r="pass"
    [ $rc -ne 0 ] && r="FAIL (rc $rc)"
    [ $rc -eq 124 ] && r="TIMEOUT ($limit s)"
    if [ $rc -ne 0 ] && [[ $name == test_* ]]; then
      r="$r: $(grep -o '^\[  FAILED  \] [A-Za-z0-9_./]*' "$out/$name.log" | sort -u | cut -c14- | head -8 | tr '\n' ' ')"
      [ $rc -gt 128 ] && r="$r crashed in $(grep '^\[ RUN      \]' "$out/$name.log" | tail -1 | cut -c14-)"
    fi
    echo "| $name | $r | $(($(date +%s) - s)) |" >>"$summary"
    if [ $rc -ne 0 ] && [ $rc -ne 124 ] && ((sanitised < 4)) && command -v compute-sanitizer >/dev/null; then
      sanitised=$((sanitised + 1))
      local args=("$@")
      if [[ $name == test_* ]]; then
        local t
        t=$(grep '^\[  FAILED  \] [A-Za-z0-9_]*\.' "$out/$name.log" | head -1 | cut -c14- | cut -d' ' -f1)
        [ -z "$t" ] && t=$(grep '^\[ RUN      \]' "$out/$name.log" | tail -1 | cut -c14-)
        [ -n "$t" ] && args+=("--gtest_filter=$t")
      fi
      timeout -s INT -k 5 60 compute-sanitizer --print-limit 3 "${args[@]}" >"$out/$name.sanitizer.log" 2>&1 || true
      echo "| $name under compute-sanitizer | see $name.sanitizer.log: $(grep -m1 -o 'Invalid.*\|Program hit.*\|ERROR SUMMARY.*' "$out/$name.sanitizer.log" | head -1 | cut -c1-120) | |" >>"$summary"
    fi
  }
  # 1. The same case on CPU and GPU: gauges over the demo's first 100 steps.
  step surge_demo_100_steps 60 surge run cases/demo_dambreak.yaml --out "$out/demo" --quiet $demo_sets
  step gauges_cpu_vs_gpu 30 python3 scripts/compare_gauges.py ref/demo/gauges.csv "$out/demo/gauges.csv" 1e-5
  # 2. Unit tests (GoogleTest binaries; the Python end-to-end tests need VTK, not there).
  for t in bin/test_*; do step "$(basename "$t")" 90 "$t"; done
  # 3. Benchmarks (JSON lines with the phase breakdown).
  step bench_demo 60 bench_sph cases/demo_dambreak.yaml 1000 1
  step bench_dambreak 60 bench_sph cases/bench_dambreak.yaml 400 1
  step bench_spheric_1e6 90 bench_sph cases/spheric_test2.yaml 200 1 --set dp=0.0102
  step bench_spheric_6e6 90 bench_sph cases/spheric_test2.yaml 50 1 --set dp=0.0056
  step bench_spheric_1.6e7 120 bench_sph cases/spheric_test2.yaml 30 1 --set dp=0.0041
  step bench_dem_1e5 60 bench_dem 100000 2000 1
  step bench_dem_hertz_1e5 40 bench_dem 100000 1000 1 hertz_mindlin
  step bench_dem_1e6 90 bench_dem 1000000 300 1
  step bench_coupling_0 60 bench_coupling 0 100 1
  step bench_coupling_1e4 60 bench_coupling 10000 100 1
  step bench_neighbour 30 bench_neighbour 1000000 1
  # 4. Validation runs: water entry at D/12 to 0.06 s (CPU build: depth 5.83 cm).
  step water_entry_d12 150 surge run cases/water_entry.yaml --out "$out/water_entry" --quiet \
    --set dp=0.0021167 --set time.end=0.06 --set time.output_every=0.06
  # 5. Archimedes at D/12 (CPU build: F_z / rho g V = 0.999 dynamic, 1.004 mdbc over 0.15-0.3 s).
  for bc in dynamic mdbc; do
    step archimedes_d12_$bc 90 surge run cases/archimedes.yaml --out "$out/arch12_$bc" --quiet \
      --set dp=0.005 --set sph.boundary=$bc --set time.output_every=0.3
  done
  {
    echo
    echo "total: $(($(date +%s) - t0)) s"
    echo
    echo "## benchmark lines"
    for f in "$out"/bench_*.log; do
      [ -f "$f" ] && echo "- $(basename "$f" .log): $(grep '^{' "$f" | tail -1)"
    done || true
    echo
    echo "## gauges, CPU vs GPU"
    tail -12 "$out/gauges_cpu_vs_gpu.log" 2>/dev/null || echo "(not run)"
    echo
    echo "## water entry D/12, last gauge row"
    tail -1 "$out/water_entry/gauges.csv" 2>/dev/null || echo "(no gauges)"
    echo
    echo "## Archimedes D/12: mean F_z / rho g V over 0.15-0.3 s"
    for bc in dynamic mdbc; do
      python3 -c "import numpy as np, math, sys; g = np.genfromtxt(sys.argv[1], delimiter=',', names=True); \
m = g['time'] >= 0.15; print(sys.argv[2], round(g['fz'][m].mean() / (1000 * 9.81 * 4 / 3 * math.pi * 0.03**3), 4))" \
        "$out/arch12_$bc/gauges.csv" $bc 2>/dev/null || echo "$bc: no result"
    done
  } >>"$summary" || true
  rm -f "$out"/*/*.vtp "$out"/*/*/*.vtp "$out"/*/*.vtk 2>/dev/null || true
  rm -rf "$out"/*/checkpoint* 2>/dev/null || true
  tar -C "$(dirname "$out")" -czf "$dest/gpu_check.tar.gz" gpu_check
  cp "$summary" "$dest/summary.md"
  cat "$summary"
}

case "${1:-}" in
  build) build ;;
  run) run ;; # from gpu_bundle/scripts, the top cd has put us in the bundle
  *)
    echo "usage: scripts/gpu_check.sh build | run" >&2
    exit 2
    ;;
esac
