"""An absorbing zone (issue 33): cases/absorbing_flume.yaml, a piston's solitary wave
(A = 0.03 m on h = 0.1 m) running into a damping zone 1.4 m long at the end of a flume
periodic across its width. At the gauges 0.8 and 1.2 m from the paddle the incident crest
passes at about 1.3 and 1.6 s; whatever the end sends back passes them again after
4-5 s. The reflected wave's height (the largest surface elevation in the window after the
incident wave and its tail have passed, smoothed over 0.1 s against the gauges' noise)
must be under 5 % of the incident one at both gauges; no water removed. --wall runs the
same flume without the zone (the end wall reflects; the check must fail) and reports it.

usage: test_absorbing.py SURGE WORKDIR CASES [--wall]"""
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import Checks  # noqa: E402

SURGE, WORK, CASES = sys.argv[1:4]
T = Checks(SURGE, WORK)
check, run = T.check, T.run
WALL = "--wall" in sys.argv[4:]




shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
case = os.path.join(CASES, "absorbing_flume.yaml")
if WALL:
    text = re.sub(r"damping:\n(  - .*\n)+", "", open(case).read())
    case = os.path.join(WORK, "reflecting_flume.yaml")
    with open(case, "w") as f:
        f.write(text)
out = os.path.join(WORK, "run")
r = subprocess.run([SURGE, "run", case, "--out", out, "--quiet"], capture_output=True, text=True)
check(r.returncode == 0, f"the flume runs (exit {r.returncode}: {r.stderr[-300:]})")
if r.returncode != 0:
    sys.exit(1)
h = 0.1
g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
t = g["time"]
dt = t[1] - t[0]
width = max(1, int(round(0.1 / dt)))
for name, x in (("H_0.8", 0.8), ("H_1.2", 1.2)):
    eta = np.convolve(g[name] - h, np.ones(width) / width, mode="same")
    k = int(np.argmax(np.where(t < 2.5, eta, -np.inf)))
    incident, t_inc = eta[k], t[k]
    # The reflection of the crest from the end (x = 3 m) arrives 2 (3 - x) / c after it.
    c = np.sqrt(9.81 * (h + 0.03))
    t_ref = t_inc + 2 * (3.0 - x) / c
    late = (t > t_ref - 1.0) & (t < t_ref + 1.0)
    reflected = eta[late].max()
    ratio = reflected / incident
    print(f"{name}: incident {incident * 1000:.1f} mm at {t_inc:.2f} s; largest elevation {reflected * 1000:.2f} mm "
          f"around {t_ref:.2f} s (+- 1 s): {100 * ratio:.1f} %")
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
