#!/usr/bin/env python3
"""One height gauge from several runs of a case, side by side: its elevation (the reading
minus the reading at t = 0) over time, and each run's crest (the largest elevation).

usage: plot_gauges.py GAUGE LABEL=GAUGES_CSV [LABEL=GAUGES_CSV ...] --png OUT.png [--end T]
GAUGES_CSV: a run's gauges.csv, or its folder. Example (docs/validation.md, slide tsunami):
  plot_gauges.py M1 paper=out/slide_paper "mdbc only"=out/slide_mdbc --end 0.7 --png m1.png
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
args = ap.parse_args()

fig, ax = plt.subplots(figsize=(7, 4))
for spec in args.runs:
    label, _, path = spec.partition("=")
    if not path:
        sys.exit(f"plot_gauges.py: '{spec}' is not LABEL=PATH")
    if os.path.isdir(path):
        path = os.path.join(path, "gauges.csv")
    g = np.genfromtxt(path, delimiter=",", names=True)
    if args.gauge not in g.dtype.names:
        sys.exit(f"plot_gauges.py: {path} has no gauge {args.gauge}")
    t, eta = g["time"], 1000 * (g[args.gauge] - g[args.gauge][0])
    keep = t <= args.end + 1e-9 if args.end is not None else np.ones(len(t), bool)
    k = np.argmax(np.where(keep, eta, -np.inf))
    print(f"{label}: {args.gauge} crest {eta[k]:.1f} mm at {t[k]:.3f} s (to {t[keep][-1]:.3f} s)")
    ax.plot(t[keep], eta[keep], label=f"{label} (crest {eta[k]:.1f} mm)")
surge_post.finish_plot(fig, ax, "t [s]", f"{args.gauge} elevation [mm]", args.png)
