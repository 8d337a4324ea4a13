"""Water entry of a sphere (paper sect. 4.1): depth of the sphere against time for runs at
several resolutions, the final-depth differences between resolutions (the paper reports
errors of 33 %, 14 %, 10 %, 10 % at D/6, D/12, D/20, D/25), and a reference curve from a
quadratic-drag model.

Depth = how far the sphere's bottom is below the still surface = 0.11 - (z - R).

The reference curve solves m dU/dt = m g - 1/2 rho C_d pi R^2 U^2 (U down, U(0) = 2.17
m/s), the cavity-phase drag law of the kind Aristoff et al. (2010) use; C_d = 0.3 is our
assumption (their paper was not available to us), so the curve is context, not data.

usage: validate_water_entry.py RUN_DIR [RUN_DIR ...] --png OUT.png
Run first: surge run cases/water_entry.yaml --out out/we6 ; ... --set dp=0.0021167 --out out/we12
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
import surge_post  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("--png", required=True)
ap.add_argument("--cd", type=float, default=0.3)
ap.add_argument("--t-final", type=float, default=0.06, help="time of the 'final' depth compared [s]")
args = ap.parse_args()

R, D, rho_s, rho, g, U0, surface = 0.0127, 0.0254, 860.0, 1000.0, 9.8, 2.17, 0.11
m = rho_s * 4.0 / 3.0 * np.pi * R**3
k = rho * args.cd * np.pi * R**2 / (2 * m)
t_ref = np.linspace(0, 0.08, 400)
ut = np.sqrt(g / k)  # terminal speed; U0 is above it
# U(t) = Ut coth(sqrt(g k) t + b), b = arccoth(U0/Ut); depth = (1/k) ln(sinh(sqrt(gk) t + b) / sinh(b))
b = 0.5 * np.log((U0 / ut + 1) / (U0 / ut - 1))
depth_ref = np.log(np.sinh(np.sqrt(g * k) * t_ref + b) / np.sinh(b)) / k

fig, ax = plt.subplots(figsize=(7, 5))
ax.plot(t_ref, depth_ref * 100, "k--", label=f"quadratic drag, C_d = {args.cd} (reference, see docstring)")
rows = []
for run in args.runs:
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    d = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    dp = surge_post.read_run_dp(run)
    depth = surface - (d["z"] - R)
    ax.plot(d["time"], depth * 100, label=f"surge dp = D/{D / dp:.0f}")
    tf = min(args.t_final, d["time"][-1])
    rows.append((D / dp, dp, s["particles"]["fluid"], s["particles"]["body"], s["steps"], s["wall_seconds"], tf,
                 float(np.interp(tf, d["time"], depth)), float(np.interp(tf, t_ref, depth_ref))))
surge_post.finish_plot(fig, ax, "t [s]", "depth of the sphere's bottom below the still surface [cm]", args.png)

rows.sort()
finest = rows[-1][7]
print("| dp | fluid particles | body particles | steps | wall time [s] | t [s] | depth [cm] | vs finest run | vs drag model |")
print("|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| D/{r[0]:.0f} | {r[2]} | {r[3]} | {r[4]} | {r[5]:.0f} | {r[6]:.3f} | {r[7] * 100:.2f} | "
          f"{(r[7] - finest) / finest * 100:+.1f} % | {(r[7] - r[8]) / r[8] * 100:+.1f} % |")
