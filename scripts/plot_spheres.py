"""Side and top views of a DEM run at a few times (sphere centres, sized by radius).
usage: plot_spheres.py RUN_DIR OUT.png [--slope-toe 3.0 --slope-deg 27.1]"""
import argparse
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
ap.add_argument("run")
ap.add_argument("png")
ap.add_argument("--slope-toe", type=float, default=None)
ap.add_argument("--slope-deg", type=float, default=27.1)
args = ap.parse_args()
frames = surge_post.read_pvd(os.path.join(args.run, "spheres.pvd"))
picks = [frames[int(round(k * (len(frames) - 1) / 3))] for k in range(4)]
fig, axes = plt.subplots(2, 1, figsize=(12, 7))
colors = plt.cm.viridis(np.linspace(0, 1, 4))
for (t, f), col in zip(picks, colors):
    d = surge_post.read_vtp(f)
    p = d["position"]
    axes[0].scatter(p[:, 0], p[:, 2], s=4, color=col, label=f"t = {t:.2f} s")
    axes[1].scatter(p[:, 0], p[:, 1], s=4, color=col)
if args.slope_toe is not None:
    x = np.array([0, args.slope_toe])
    axes[0].plot(x, (args.slope_toe - x) * math.tan(math.radians(args.slope_deg)), "k-", lw=1)
axes[0].axhline(0, color="k", lw=1)
axes[0].set_xlabel("x [m]")
axes[0].set_ylabel("z [m]")
axes[0].set_aspect("equal")
axes[0].legend()
axes[1].set_xlabel("x [m]")
axes[1].set_ylabel("y [m]")
axes[1].set_aspect("equal")
last = surge_post.read_vtp(frames[-1][1])["position"]
axes[1].set_title(f"deposit at t = {frames[-1][0]:.2f} s: front x = {last[:, 0].max():.2f} m, "
                  f"mean thickness {np.ptp(last[:, 2]):.2f} m (centres)")
fig.tight_layout()
fig.savefig(args.png, dpi=90)
print(f"wrote {args.png}; final front x = {last[:, 0].max():.3f} m, tail x = {last[:, 0].min():.3f} m")
