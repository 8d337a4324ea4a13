"""SPHERIC test 2 (cases/spheric_test2.yaml): the flow that meets the box's front face
(x = 0.8245 m) on the pressure plateau, from a run's fluid frames between --from and
--to (0.5-0.8 s by default). In a slab 0.86-0.99 m in x (up to H2) across the box's
width (0.2955 < y < 0.6985 m): the water's depth (the particles' volume over the slab's
area), the mean x velocity, its rms, and the mean x velocity of the layer below 5 cm
(where P1 and P2 sit), with rho g d and rho <u^2> / 2 in kPa, the two parts of the
momentum that the face stops.

usage: spheric_inflow.py RUN_DIR [RUN_DIR ...] [--from 0.5] [--to 0.8]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import surge_post  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("--from", dest="t0", type=float, default=0.5)
ap.add_argument("--to", dest="t1", type=float, default=0.8)
args = ap.parse_args()
X0, X1, Y0, Y1, LOW = 0.86, 0.99, 0.2955, 0.6985, 0.05
RHO, G = 1000.0, 9.81
for run in args.runs:
    dp = surge_post.read_run_dp(run)
    rows = []
    for _, f in surge_post.read_frames(run, args.t0, args.t1):
        p, v = f["position"], f["velocity"]
        slab = (p[:, 0] > X0) & (p[:, 0] < X1) & (p[:, 1] > Y0) & (p[:, 1] < Y1)
        low = slab & (p[:, 2] < LOW)
        ux = v[slab, 0]
        rows.append((slab.sum() * dp**3 / ((X1 - X0) * (Y1 - Y0)), ux.mean(), (ux**2).mean(), v[low, 0].mean()))
    if not rows:
        sys.exit(f"spheric_inflow.py: {run} has no frame in [{args.t0}, {args.t1}] s")
    depth, u, u2, ulow = np.mean(rows, axis=0)
    print(f"{os.path.basename(os.path.normpath(run))}: {len(rows)} frames, depth {100 * depth:.1f} cm, "
          f"<u_x> {u:+.2f} m/s, rms {np.sqrt(u2):.2f} m/s, below {100 * LOW:.0f} cm {ulow:+.2f} m/s; "
          f"rho g d {RHO * G * depth / 1000:.2f} kPa, rho <u^2>/2 {RHO * u2 / 2000:.2f} kPa")
