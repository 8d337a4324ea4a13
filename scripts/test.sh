#!/usr/bin/env bash
# Installs what is missing, builds the CPU preset with warnings as errors and runs the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake --preset cpu-ci
cmake --build --preset cpu-ci -j"$(nproc)"
ctest --preset cpu-ci -j1
