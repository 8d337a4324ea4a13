"""An absorbing zone (issue 33): cases/absorbing_flume.yaml, a piston's solitary wave
(A = 0.03 m on h = 0.1 m) running into a damping zone 1.4 m long at the end of a flume
periodic across its width. At the gauges 0.8 and 1.2 m from the paddle the incident crest
passes at about 1.4 and 1.7 s; whatever the end sends back passes them again
2 (3 m - x) / c later (about 5.2 and 4.9 s). The reflected wave's height: the largest
surface elevation within 0.6 s of that time, above the level there (the straight line
between the means over the window's first and last 0.2 s), the gauges smoothed over
0.1 s against their noise; it must be under 5 % of the incident crest at both gauges.

The level itself rises meanwhile: a zone that damps velocity keeps the wave's mass, which
spreads back from the zone as a slow set-up, and the paddle, which stays where its stroke
ended, has raised the still level of this closed flume by h S / (L - S) = 4.5 mm anyway
(L the water's length, S the stroke). The test reports the level against that, and no
water removed. --wall runs the same flume without the zone: the end wall sends the wave
back and the check fails (47 % and 55 % on 2026-12-04; the zone 2.6 % and 3.1 %).
--coarse runs the flume at dp = 1.25 cm (8 dp per depth, the slab 5 dp wide: about 4
minutes on 2 cores instead of 20, the validation label's variant).

usage: test_absorbing.py SURGE WORKDIR CASES [--wall] [--coarse]"""
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import Checks  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import surge_post  # noqa: E402

SURGE, WORK, CASES = sys.argv[1:4]
T = Checks(SURGE, WORK)
check, run = T.check, T.run
WALL = "--wall" in sys.argv[4:]
COARSE = "--coarse" in sys.argv[4:]




shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
case = os.path.join(CASES, "absorbing_flume.yaml")
if WALL or COARSE:
    text = open(case).read()
    if WALL:
        text = re.sub(r"damping:\n(  - .*\n)+", "", text)
    if COARSE:  # dp 1.25 cm; the periodic slab 5 dp wide (at least 4 h), the gauges on its middle
        text = (text.replace("dp: 0.01\n", "dp: 0.0125\n").replace("y: 0.025}", "y: 0.03125}")
                .replace(", 0.05, 0.", ", 0.0625, 0."))
        assert text.count("0.0625") == 4
    case = os.path.join(WORK, "flume.yaml")
    with open(case, "w") as f:
        f.write(text)
out = os.path.join(WORK, "run")
r = subprocess.run([SURGE, "run", case, "--out", out, "--quiet"], capture_output=True, text=True)
check(r.returncode == 0, f"the flume runs (exit {r.returncode}: {r.stderr[-300:]})")
if r.returncode != 0:
    sys.exit(1)
h = 0.1
names, data = surge_post.read_gauges(os.path.join(out, "gauges.csv"))  # names keep their dots
g = {n: data[:, k] for k, n in enumerate(names)}
t = g["time"]
dt = t[1] - t[0]
width = max(1, int(round(0.1 / dt)))
c = np.sqrt(9.81 * (h + 0.03))
stroke, length = 0.12645, 3.0 - 0.06
h_end = h * length / (length - stroke)  # the still level once the paddle has stopped
for name, x in (("H_0.8", 0.8), ("H_1.2", 1.2)):
    eta = np.convolve(g[name] - h, np.ones(width) / width, mode="same")
    k = int(np.argmax(np.where(t < 2.5, eta, -np.inf)))
    incident, t_inc = eta[k], t[k]
    # The reflection of the crest from the end (x = 3 m) would arrive 2 (3 - x) / c after it.
    t_ref = t_inc + 2 * (3.0 - x) / c
    win = (t >= t_ref - 0.6) & (t <= t_ref + 0.6)
    tw, ew = t[win], eta[win]
    check(len(tw) > 0 and tw[-1] >= t_ref + 0.6 - 2 * dt, f"{name}: the run covers the return window (to {t_ref + 0.6:.2f} s)")
    head, tail = tw <= tw[0] + 0.2, tw >= tw[-1] - 0.2
    t0, e0, t1, e1 = tw[head].mean(), ew[head].mean(), tw[tail].mean(), ew[tail].mean()
    level = e0 + (e1 - e0) * (tw - t0) / (t1 - t0)
    reflected = (ew - level).max()
    ratio = reflected / incident
    print(f"{name}: incident {incident * 1000:.1f} mm at {t_inc:.2f} s; around {t_ref:.2f} s the level rises "
          f"{(e1 - e0) * 1000:+.2f} mm to {(h + e1 - h_end) * 1000:+.2f} mm of the final still level h_end "
          f"= {h_end:.4f} m; largest elevation above it {reflected * 1000:.2f} mm")
    check(ratio < 0.05, f"{name}: reflected {100 * ratio:.1f} % of the incident height (< 5 %)")
s = json.load(open(os.path.join(out, "summary.json")))
check(s["removed"]["total"] == 0, f"no water removed ({s['removed']})")
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 3.2))
    for name in ("H_0.8", "H_1.2", "H_2.0"):
        ax.plot(t, (g[name] - h) * 1000, label=name.replace("H_", "x = ") + " m")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("surface elevation [mm]")
    ax.set_title("Solitary wave into " + ("the end wall" if WALL else "a 1.4 m absorbing zone (x > 1.6 m)"))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(WORK, "absorbing.png"), dpi=110)
except ImportError:
    pass
T.finish("absorbing-zone")
