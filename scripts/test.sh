#!/usr/bin/env bash
# Installs what is missing, builds the CPU preset with warnings as errors and runs the quick
# tests (every unit test and the end-to-end CLI test; a few minutes on 2 cores). The long
# validation tests (dam-break front against Koshizuka & Oka, moving and floating bodies, the
# reservoir) carry the ctest label "validation" (`ctest --preset cpu-ci -L validation`),
# the longest ones (coupled cases, walls holding water, the full floating box) "long";
# scripts/test.sh --all runs every one of them.
# Tests labelled "open" are acceptance tests of open issues that do not pass yet
# (tests/CMakeLists.txt says why; none today): `ctest --preset cpu-ci -L open`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
# Two tests at a time: each run uses every core, and a waiting thread must yield (PASSIVE)
# or two OpenMP runs on two cores spin against each other.
export OMP_WAIT_POLICY=PASSIVE
cmake --preset cpu-ci
cmake --build --preset cpu-ci -j"$(nproc)"
if [ "${1:-}" = "--all" ]; then
  ctest --preset cpu-ci -j2 -LE open
else
  ctest --preset cpu-ci -j2 -LE "validation|long|open"
fi
