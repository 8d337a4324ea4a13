#!/usr/bin/env bash
# Installs what is missing, builds surge (CPU preset), runs the small demo dam break
# and plots it: out/demo_dambreak/ (VTK, gauges.csv, summary.json) and demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake --preset cpu
cmake --build --preset cpu -j"$(nproc)"
./build/cpu/src/surge/surge run cases/demo_dambreak.yaml --out out/demo_dambreak
/usr/bin/python3 scripts/plot_demo.py out/demo_dambreak out/demo_dambreak/demo.png
echo "demo output: out/demo_dambreak/ (open fluid.pvd in ParaView), plot: out/demo_dambreak/demo.png"
