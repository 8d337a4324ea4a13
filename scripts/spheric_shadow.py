"""SPHERIC test 2 (cases/spheric_test2.yaml): where the water behind the box goes before it
reaches H1 (x = 0.496 m, behind the box's centre). For each frame between --from and --to:
the fluid particles in the box's shadow (x < 0.6635 m, 0.2955 < y < 0.6985 m) above 0.15 m
(jets and water climbing the end wall), the 99th percentile of the height of the water
within 5 cm of the end wall (its run-up), and the particles on the bed (z < 0.15 m) within
5.5 cm of H1's x in the shadow.

usage: spheric_shadow.py RUN_DIR [RUN_DIR ...] [--from 0.85] [--to 1.15]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import surge_post  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("--from", dest="t0", type=float, default=0.85)
ap.add_argument("--to", dest="t1", type=float, default=1.15)
args = ap.parse_args()
BOX_X, BOX_Y0, BOX_Y1, H1_X = 0.6635, 0.2955, 0.6985, 0.496
for run in args.runs:
    print(os.path.basename(os.path.normpath(run)))
    for t, f in surge_post.read_frames(run, args.t0, args.t1):
        p = f["position"]
        shadow = p[(p[:, 0] < BOX_X) & (p[:, 1] > BOX_Y0) & (p[:, 1] < BOX_Y1)]
        wall = p[p[:, 0] < 0.05]
        runup = np.percentile(wall[:, 2], 99) if len(wall) else 0.0
        bed = shadow[(shadow[:, 2] < 0.15) & (np.abs(shadow[:, 0] - H1_X) < 0.055)]
        print(f"  t = {t:.2f} s: shadow above 0.15 m {np.sum(shadow[:, 2] >= 0.15):5d} particles, "
              f"end-wall run-up (z99) {100 * runup:5.1f} cm, on the bed at H1 {len(bed):4d}")
