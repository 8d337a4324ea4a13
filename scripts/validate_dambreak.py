"""Dam break I (Koshizuka & Oka 1996): surge front of a finished run against the
measured fronts of Koshizuka & Oka and Martin & Moyce. Writes a PNG and prints a
Markdown table of errors.

usage: validate_dambreak.py RUN_DIR [RUN_DIR ...] --png OUT.png [--data data]
Run first, e.g.: surge run cases/dambreak_koshizuka.yaml --set time.end=0.4 --set time.output_every=0.01
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
ap.add_argument("runs", nargs="+")
ap.add_argument("--png", required=True)
ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "data"))
ap.add_argument("--a", type=float, default=0.146, help="initial column width [m]")
ap.add_argument("--tank", type=float, default=0.584, help="tank length [m]")
args = ap.parse_args()

a, g = args.a, 9.81
scale = np.sqrt(2 * g / a)
ko = surge_post.read_front_data(os.path.join(args.data, "koshizuka_oka_1996_front.txt"))
mm1 = surge_post.read_front_data(os.path.join(args.data, "martin_moyce_1952_a1.125in.txt"))
mm2 = surge_post.read_front_data(os.path.join(args.data, "martin_moyce_1952_a2.25in.txt"))

fig, ax = plt.subplots(figsize=(7, 5))
ax.plot(ko[:, 0], ko[:, 1], "ks", label="Koshizuka & Oka 1996")
ax.plot(mm1[:, 0], mm1[:, 1], "b^", mfc="none", label="Martin & Moyce 1952, a = 1.125 in")
ax.plot(mm2[:, 0], mm2[:, 1], "bv", mfc="none", label="Martin & Moyce 1952, a = 2.25 in")
print("| run | dp [mm] | particles (fluid) | steps | wall time [s] | RMS front error vs KO [% of a] | max rel. error vs KO | max rel. error vs MM (2.25 in) |")
print("|---|---|---|---|---|---|---|---|")
for run in args.runs:
    case_text = open(os.path.join(run, "case.yaml")).read()
    dp = float([l for l in case_text.splitlines() if l.startswith("dp:")][0].split(":")[1])
    T, Z = [], []
    for t, f in surge_post.read_pvd(os.path.join(run, "fluid.pvd")):
        T.append(t * scale)
        Z.append(surge_post.surge_front(surge_post.read_vtp(f)["position"], dp) / a)
    T, Z = np.array(T), np.array(Z)
    s = surge_post.read_summary(os.path.join(run, "summary.json"))
    label = f"surge, dp = {1000 * dp:.2f} mm"
    ax.plot(T, Z, "-", label=label)

    def errors(data):
        sel = (data[:, 1] * a < 0.95 * args.tank) & (data[:, 0] <= T.max())
        d = data[sel]
        zs = np.interp(d[:, 0], T, Z)
        return np.sqrt(np.mean((zs - d[:, 1]) ** 2)), np.max(np.abs(zs - d[:, 1]) / d[:, 1])

    rms_ko, max_ko = errors(ko)
    _, max_mm = errors(mm2)
    print(f"| {os.path.basename(run.rstrip('/'))} | {1000 * dp:.2f} | {s['particles']['fluid']} | {s['steps']} | "
          f"{s['wall_seconds']:.0f} | {100 * rms_ko:.1f} | {100 * max_ko:.1f} % | {100 * max_mm:.1f} % |")
ax.axhline(args.tank / a, color="0.5", ls=":", label="far wall")
ax.set_xlabel("T = t sqrt(2g/a)")
ax.set_ylabel("Z = front / a")
ax.set_xlim(0, 3.5)
ax.set_ylim(0.8, 4.2)
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(args.png, dpi=100)
print(f"\nwrote {args.png}")
