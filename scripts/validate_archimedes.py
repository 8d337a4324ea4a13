"""Archimedes (cases/archimedes.yaml): vertical fluid force on a fixed submerged sphere
against rho g V, at several resolutions, and where the effective surface sits:
r_eff = R (F / rho g V)^(1/3), reported as R + x dp.

usage: validate_archimedes.py RUN_DIR [RUN_DIR ...] --png OUT.png [--from 0.15]
Run first: surge run cases/archimedes.yaml --out out/arch6 ; --set dp=0.005 --out out/arch12 ; dp=0.003 (D/20)
"""
import argparse
import json
import math
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
ap.add_argument("--from", dest="t0", type=float, default=0.15, help="average the force from this time on [s]")
args = ap.parse_args()

R, D, rho, g = 0.03, 0.06, 1000.0, 9.81
fb = rho * g * 4.0 / 3.0 * math.pi * R**3
fig, ax = plt.subplots(figsize=(7, 4.5))
rows = []
for run in args.runs:
    with open(os.path.join(run, "summary.json")) as f:
        s = json.load(f)
    dp = surge_post.read_run_dp(run)
    d = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    ax.plot(d["time"], d["fz"] / fb, label=f"dp = D/{D / dp:.0f}")
    m = d["time"] >= args.t0
    ratio = d["fz"][m].mean() / fb
    r_eff = R * ratio ** (1 / 3)
    rows.append((D / dp, s["particles"]["fluid"], s["particles"]["body"], s["steps"], s["wall_seconds"], ratio,
                 d["fz"][m].std() / fb, (r_eff - R) / dp, (r_eff - R) * 1000))
ax.axhline(1.0, color="k", ls="--", label="rho g V")
ax.set_ylim(0, 2.5)
surge_post.finish_plot(fig, ax, "t [s]", "F_z / (rho g V)", args.png)
rows.sort()
print(f"| dp | fluid | body | steps | wall [s] | F_z / rho g V (t >= {args.t0} s) | std | r_eff - R [dp] | r_eff - R [mm] |")
print("|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| D/{r[0]:.0f} | {r[1]} | {r[2]} | {r[3]} | {r[4]:.0f} | {r[5]:.3f} ({(r[5] - 1) * 100:+.1f} %) | {r[6]:.3f} | "
          f"{r[7]:+.2f} | {r[8]:+.2f} |")
