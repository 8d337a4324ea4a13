"""Plots a finished dam-break run: four snapshots (side view) and the gauges.
usage: plot_demo.py RUN_DIR OUT.png"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
import surge_post  # noqa: E402

run, png = sys.argv[1], sys.argv[2]
frames = surge_post.read_pvd(os.path.join(run, "fluid.pvd"))
walls = surge_post.read_vtp(surge_post.read_pvd(os.path.join(run, "walls.pvd"))[0][1])
picks = [frames[int(round(k * (len(frames) - 1) / 3))] for k in range(4)]
fig, axes = plt.subplots(2, 3, figsize=(15, 7))
for ax, (t, f) in zip(axes.flat[:4], picks):
    d = surge_post.read_vtp(f)
    ax.scatter(walls["position"][:, 0], walls["position"][:, 2], s=1, c="0.7")
    sc = ax.scatter(d["position"][:, 0], d["position"][:, 2], s=2, c=np.linalg.norm(d["velocity"], axis=1), cmap="viridis",
                    vmin=0, vmax=3)
    ax.set_title(f"t = {t:.2f} s")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
fig.colorbar(sc, ax=axes.flat[3], label="|v| [m/s]")
names, g = surge_post.read_gauges(os.path.join(run, "gauges.csv"))
for k, name in enumerate(names[1:], start=1):
    ax = axes.flat[4] if k == 1 else axes.flat[5]
    ax.plot(g[:, 0], g[:, k], label=name)
axes.flat[4].set_xlabel("t [s]")
axes.flat[4].set_ylabel("height gauge z [m]")
axes.flat[5].set_xlabel("t [s]")
axes.flat[5].set_ylabel("pressure [Pa] / force [N]")
for ax in axes.flat[4:]:
    ax.legend()
s = surge_post.read_summary(os.path.join(run, "summary.json"))
fig.suptitle(f"{s['name']}: {s['particles']['fluid']} fluid + {s['particles']['wall']} wall particles, "
             f"{s['steps']} steps in {s['wall_seconds']:.0f} s")
fig.tight_layout()
fig.savefig(png, dpi=90)
print(f"wrote {png}")
