"""Runout of finished granular column collapses against Lube et al. (2005, Phys. Rev. E
72, 041301, quasi-2D columns): (L_inf - L0)/L0 = 1.6 a for a < 2.3, 2.2 a^(2/3) beyond.
usage: column_runout.py RUN_DIR [RUN_DIR ...] --png OUT.png"""
import argparse
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
args = ap.parse_args()


def lube(a):
    return np.where(a < 2.3, 1.6 * a, 2.2 * a ** (2.0 / 3.0))


fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(13, 4.5))
print("| run | a = H0/L0 | L0 [m] | L_inf [m] | (L_inf - L0)/L0 surge | Lube et al. 2005 | ratio | spheres ahead of the deposit |")
print("|---|---|---|---|---|---|---|---|")
rows = []
for run in args.runs:
    frames = surge_post.read_pvd(os.path.join(run, "spheres.pvd"))
    first, last = surge_post.read_vtp(frames[0][1]), surge_post.read_vtp(frames[-1][1])
    r = float(first["radius"].max())
    L0 = first["position"][:, 0].max() + r
    H0 = first["position"][:, 2].max() + r
    # Front of the continuous deposit: single spheres that rolled away ahead of it (a
    # gap of more than two diameters along x) are not part of the runout.
    xs = np.sort(last["position"][:, 0])
    gaps = np.nonzero(np.diff(xs) > 4 * r)[0]
    L = (xs[gaps[0]] if len(gaps) else xs[-1]) + r
    ahead = len(xs) - 1 - (gaps[0] if len(gaps) else len(xs) - 1)
    a = H0 / L0
    rel = (L - L0) / L0
    name = os.path.basename(run.rstrip('/'))
    rows.append((a, rel, name))
    print(f"| {name} | {a:.2f} | {L0:.3f} | {L:.3f} | {rel:.2f} | {float(lube(a)):.2f} | {rel / float(lube(a)):.2f} | {ahead} |")
    ax1.scatter(last["position"][:, 0], last["position"][:, 2], s=3, label=f"{name}: a = {a:.1f}, t = {frames[-1][0]:.2f} s")
aa = np.linspace(0.3, 4, 100)
ax0.plot(aa, lube(aa), "k-", label="Lube et al. 2005")
markers = "os^vD<>"
for k, (a, rel, name) in enumerate(rows):
    ax0.plot(a, rel, markers[k % len(markers)], label=name)
ax0.set_xlabel("a = H0 / L0")
ax0.set_ylabel("(L_inf - L0) / L0")
ax0.legend()
ax0.grid(alpha=0.3)
ax1.set_xlabel("x [m]")
ax1.set_ylabel("z [m]")
ax1.set_aspect("equal")
ax1.legend()
fig.tight_layout()
fig.savefig(args.png, dpi=90)
print(f"\nwrote {args.png}")
