"""Slide tsunami (cases/slide_tsunami.yaml): free-surface elevation at M1-M4 for runs at
several dp/D (elevation = gauge reading minus its reading at t = 0, which removes the
gauge's offset from the nominal 0.4 m: the kernel fraction reaches 0.5 about 0.6 dp below
the top particle layer's nominal surface), and the slide (sphere centres, side view) at the last common time of the
runs. Prints the largest elevation at each gauge and the RMS difference of each run from
the finest one (the paper finds the far-field gauges M2-M4 nearly identical across dp/D).

usage: validate_slide.py RUN_DIR [RUN_DIR ...] --png OUT.png [--labels LABEL ...]
With --labels (one per run: runs of one dp with other settings) the runs keep their order
and the RMS differences are taken against the first.
Run first: surge run cases/slide_tsunami.yaml --out out/slide4 ; --set dp=0.01 --out out/slide6
"""
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
ap.add_argument("runs", nargs="+")
ap.add_argument("--png", required=True)
ap.add_argument("--still", type=float, default=0.4, help="still-water depth [m]")
ap.add_argument("--labels", nargs="+", help="one per run; the runs keep their order, compared with the first")
args = ap.parse_args()
if args.labels and len(args.labels) != len(args.runs):
    sys.exit("validate_slide.py: --labels needs one label per run")

D = 0.06
runs = []
for k, run in enumerate(args.runs):
    dp = surge_post.read_run_dp(run)
    names, g = surge_post.read_gauges(os.path.join(run, "gauges.csv"))
    label = args.labels[k] if args.labels else f"dp = D/{D / dp:.0f}"
    runs.append((dp, run, names, g, surge_post.read_summary(os.path.join(run, "summary.json")), label))
if not args.labels:
    runs.sort(key=lambda r: r[0], reverse=True)
reference = runs[0] if args.labels else runs[-1]  # the first given, or the finest dp
gauges = ["M1", "M2", "M3", "M4"]
fig, axes = plt.subplots(3, 2, figsize=(12, 10))
for k, name in enumerate(gauges):
    ax = axes[k // 2][k % 2]
    for dp, run, names, g, s, label in runs:
        col = g[:, names.index(name)]
        ax.plot(g[:, 0], col - col[0], label=label)
    ax.set_title(name)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("elevation [m]")
    ax.grid(alpha=0.3)
    ax.legend()
t_common = min(g[-1, 0] for _, _, _, g, _, _ in runs)
ax = axes[2][0]
for dp, run, names, g, s, label in runs:
    frames = surge_post.read_pvd(os.path.join(run, "spheres.pvd"))
    t, f = min(frames, key=lambda x: abs(x[0] - t_common))
    p = surge_post.read_vtp(f)["position"]
    ax.scatter(p[:, 0], p[:, 2], s=3, label=f"{label}, t = {t:.2f} s")
x = np.linspace(0, 3.0, 10)
ax.plot(x, (3.0 - x) * math.tan(math.radians(27.1)), "k-", lw=1)
ax.axhline(args.still, color="b", lw=0.5)
ax.set_xlim(1.5, 4.5)
ax.set_ylim(-0.05, 1.0)
ax.set_aspect("equal")
ax.set_title("slide (sphere centres), side view")
ax.legend(fontsize=8)
axes[2][1].axis("off")
fig.tight_layout()
fig.savefig(args.png, dpi=110)

print("| run | fluid | body | steps | simulated [s] | wall [s] | " + " | ".join(f"max {n} [mm]" for n in gauges)
      + " | " + " | ".join(f"RMS diff {n} vs {'the first' if args.labels else 'finest'} [mm]" for n in gauges) + " |")
print("|---" * (6 + 2 * len(gauges)) + "|")
for dp, run, names, g, s, label in runs:
    cells = [label, str(s["particles"]["fluid"]), str(s["particles"]["body"]), str(s["steps"]),
             f"{g[-1, 0]:.2f}", f"{s['wall_seconds']:.0f}"]
    cells += [f"{(g[:, names.index(n)].max() - g[0, names.index(n)]) * 1000:.1f}" for n in gauges]
    for n in gauges:
        tf, gf = reference[3][:, 0], reference[3][:, reference[2].index(n)]
        tmax = min(tf[-1], g[-1, 0])
        tt = np.linspace(0, tmax, 200)
        diff = (np.interp(tt, g[:, 0], g[:, names.index(n)]) - g[0, names.index(n)]) - (np.interp(tt, tf, gf) - gf[0])
        cells.append(f"{math.sqrt(np.mean(diff**2)) * 1000:.1f}")
    print("| " + " | ".join(cells) + " |")
