#!/usr/bin/env python3
"""Height gauges from several runs of a case, side by side: each gauge's elevation (the
reading minus the reading at t = 0) over time, and each run's crest (the largest elevation).

usage: plot_gauges.py GAUGE[,GAUGE...] LABEL=GAUGES_CSV [LABEL=GAUGES_CSV ...] --png OUT.png [--end T] [--floor MM]
GAUGES_CSV: a run's gauges.csv, or its folder. --floor MM: elevations below MM are drawn
as gaps, their count printed (a gauge that read the dry bed, not the water). Several gauges (comma-separated): one panel
each, two to a row. Examples (docs/validation.md, slide tsunami):
  plot_gauges.py M1 paper=out/slide_paper "mdbc only"=out/slide_mdbc --end 0.7 --png m1.png
  plot_gauges.py M1,M2,M3,M4 paper=out/slide_paper recommended=docs/runs/slide_tsunami_recommended_gauges.csv --png m.png
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import surge_post  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("gauge")
ap.add_argument("runs", nargs="+", help="LABEL=path to gauges.csv or its run folder")
ap.add_argument("--png", required=True)
ap.add_argument("--end", type=float, default=None, help="last time shown [s]")
ap.add_argument("--floor", type=float, default=None, help="elevations below this [mm] are gaps")
args = ap.parse_args()

gauges = args.gauge.split(",")
rows = (len(gauges) + 1) // 2
cols = 1 if len(gauges) == 1 else 2
fig, axes = plt.subplots(rows, cols, figsize=(7 * cols, 4 * rows), squeeze=False)
for spec in args.runs:
    label, _, path = spec.partition("=")
    if not path:
        sys.exit(f"plot_gauges.py: '{spec}' is not LABEL=PATH")
    if os.path.isdir(path):
        path = os.path.join(path, "gauges.csv")
    g = np.genfromtxt(path, delimiter=",", names=True)
    for n, gauge in enumerate(gauges):
        if gauge not in g.dtype.names:
            sys.exit(f"plot_gauges.py: {path} has no gauge {gauge}")
        t, eta = g["time"], 1000 * (g[gauge] - g[gauge][0])
        keep = t <= args.end + 1e-9 if args.end is not None else np.ones(len(t), bool)
        k = np.argmax(np.where(keep, eta, -np.inf))
        print(f"{label}: {gauge} crest {eta[k]:.1f} mm at {t[k]:.3f} s (to {t[keep][-1]:.3f} s)")
        shown = eta.copy()
        if args.floor is not None:
            dry = keep & (eta < args.floor)
            if dry.any():
                print(f"{label}: {gauge} {dry.sum()} samples below {args.floor:g} mm left out: {t[dry]}")
            shown[dry] = np.nan
        axes[n // cols][n % cols].plot(t[keep], shown[keep], label=f"{label} (crest {eta[k]:.1f} mm)")
for n, gauge in enumerate(gauges):
    surge_post.style_axes(axes[n // cols][n % cols], "t [s]", f"{gauge} elevation [mm]")
if len(gauges) % 2 == 1 and cols == 2:
    axes[-1][-1].axis("off")
fig.tight_layout()
fig.savefig(args.png, dpi=120)
