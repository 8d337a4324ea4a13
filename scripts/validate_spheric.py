"""SPHERIC test 2 (Kleefsman et al. 2005): gauges H1-H4 and P1-P8 of a finished run
against the MARIN measurements. The file's H1 and H3 labels are swapped (see
data/README.md): its "H1" column is the gauge at x = 1.488 m (our H3) and
its "H3" column the gauge at x = 0.496 m (our H1). Writes a PNG and prints a
Markdown table: normalised RMS over the common time range (at most 0-6 s), arrival
time and peak errors. Height gauges H1h..H4h, if the run has them (the same lines with
`surface: highest`), are tabulated and drawn beside the default column reading.

usage: validate_spheric.py RUN_DIR --png OUT.png [--data data]
"""
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
ap.add_argument("run")
ap.add_argument("--png", required=True)
ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "data"))
ap.add_argument("--tmax", type=float, default=6.0)
args = ap.parse_args()

exp = np.loadtxt(os.path.join(args.data, "spheric_test2_kleefsman_exp.dat"), skiprows=2)
cols = {"P%d" % k: k for k in range(1, 9)}
cols.update({"H3": 9, "H2": 10, "H1": 11, "H4": 12})  # label swap H1 <-> H3 in the file
names, sim = surge_post.read_gauges(os.path.join(args.run, "gauges.csv"))
tsim = sim[:, 0]
tmax = min(args.tmax, tsim.max())
s = surge_post.read_summary(os.path.join(args.run, "summary.json"))


def arrival(t, y, thr):
    idx = np.nonzero(y > thr)[0]
    return t[idx[0]] if len(idx) else np.nan


print(f"run {args.run}: {s['particles']['fluid']} fluid + {s['particles']['wall']} wall particles, "
      f"t = 0-{tmax:.2f} s compared, {s['steps']} steps, {s['wall_seconds']:.0f} s wall\n")
print("| gauge | NRMS (RMS / measured range) | arrival exp [s] | arrival sim [s] | peak exp | peak sim | peak error |")
print("|---|---|---|---|---|---|---|")
fig, axes = plt.subplots(4, 3, figsize=(15, 12))
order = ["H1", "H2", "H3", "H4", "P1", "P2", "P3", "P4", "P5", "P6", "P7", "P8"]
hi = "h" if "H1h" in names else "hi"  # the highest-point readings: H1h.. or H1hi..
rows = [(n, n) for n in order[:4]] + [(n + hi, n) for n in order[:4] if n + hi in names] + [(n, n) for n in order[4:]]
axes_of = {n: ax for n, ax in zip(order, axes.flat)}
for col, name in rows:
    ax = axes_of[name]
    highest = col != name
    te, ye = exp[:, 0], exp[:, cols[name]]
    sel = te <= tmax
    te, ye = te[sel], ye[sel]
    ys = np.interp(te, tsim, sim[:, names.index(col)])
    nrms = np.sqrt(np.mean((ys - ye) ** 2)) / (ye.max() - ye.min())
    if name.startswith("H"):
        # heights: arrival when the water first rises 2 cm above the gauge's initial level
        thr_e, thr_s = ye[0] + 0.02, ys[0] + 0.02
        unit = "m"
    else:
        thr_e = thr_s = 1000.0  # pressure: first exceeds 1 kPa
        unit = "Pa"
    ae, as_ = arrival(te, ye, thr_e), arrival(te, ys, thr_s)
    pe, ps = ye.max(), ys.max()
    print(f"| {name}{' (surface: highest)' if highest else ''} | {nrms:.3f} | {ae:.3f} | {as_:.3f} | {pe:.4g} {unit} | {ps:.4g} {unit} | {100 * (ps - pe) / pe:+.0f} % |")
    if highest:
        ax.plot(tsim[tsim <= tmax], sim[tsim <= tmax, names.index(col)], "b:", lw=0.8, label="surge, surface: highest")
        continue
    ax.plot(te, ye, "k-", lw=0.8, label="experiment (MARIN)")
    ax.plot(tsim[tsim <= tmax], sim[tsim <= tmax, names.index(col)], "r-", lw=1, label="surge (column)")
    ax.set_title(name)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("z [m]" if unit == "m" else "p [Pa]")
    ax.grid(alpha=0.3)
axes.flat[0].legend(fontsize=8)
fig.suptitle(f"SPHERIC test 2, {s['particles']['fluid']} fluid particles")
fig.tight_layout()
fig.savefig(args.png, dpi=80)
print(f"\nwrote {args.png}")
