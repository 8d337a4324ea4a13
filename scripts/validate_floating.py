"""Floating sphere (cases/floating.yaml): displaced volume against V/2.

The draught is d = surface - (z - R), with the free surface read by the height gauge
near a corner; the displaced volume is the spherical cap pi d^2 (3R - d) / 3. Averages
over the last half of the run (the sphere heaves about its equilibrium).

usage: validate_floating.py RUN_DIR [RUN_DIR ...] [--png OUT.png] [--from 0.5]
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import surge_post  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("--png")
ap.add_argument("--from", dest="t0", type=float, default=0.5)
args = ap.parse_args()
R, D = 0.03, 0.06
V = 4 / 3 * math.pi * R**3
rows = []
curves = []
for run in args.runs:
    dp = surge_post.read_run_dp(run)
    g = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    d = g["surface"] - (g["z"] - R)
    cap = math.pi * d**2 * (3 * R - d) / 3
    m = g["time"] >= args.t0
    rows.append((D / dp, cap[m].mean() / V, cap[m].std() / V, g["fz"][m].mean(), g["time"][-1]))
    curves.append((D / dp, g["time"], cap / V))
print(f"| dp | displaced volume / V (t >= {args.t0} s) | heave (std / V) | mean fluid force [N] | run to [s] |")
print("|---|---|---|---|---|")
for r in sorted(rows):
    print(f"| D/{r[0]:.0f} | {r[1]:.3f} ({(r[1] / 0.5 - 1) * 100:+.1f} % vs 1/2) | {r[2]:.3f} | {r[3]:.4f} | {r[4]:.2f} |")
print(f"(weight of the sphere: {500 * V * 9.81:.4f} N)")
if args.png:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    for k, t, c in sorted(curves, key=lambda x: x[0]):
        ax.plot(t, c, label=f"dp = D/{k:.0f}")
    ax.axhline(0.5, color="k", ls="--", label="V/2")
    surge_post.finish_plot(fig, ax, "t [s]", "displaced volume / V", args.png)
