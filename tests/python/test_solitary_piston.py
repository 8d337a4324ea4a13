"""A piston wave-maker with Goring's solitary-wave stroke (cases/solitary_piston.yaml:
A/h = 0.2, h = 12 dp, mdbc): the wave's height at the gauge 5 depths downstream within
10 % of A, and its celerity between the gauges at 5 and 10 depths within 3 % of
sqrt(g (h + A)) (issue 34). Crest times from a parabola through the three samples around
each gauge's maximum. Writes solitary_piston.png (gauges against the first-order profile
A sech^2(k (x - c t))) into the work folder when matplotlib is there.

usage: test_solitary_piston.py SURGE WORKDIR CASES"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

SURGE, WORK, CASES = sys.argv[1:4]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
out = os.path.join(WORK, "run")
r = subprocess.run([SURGE, "run", os.path.join(CASES, "solitary_piston.yaml"), "--out", out, "--quiet"],
                   capture_output=True, text=True)
check(r.returncode == 0, f"the piston case runs (exit {r.returncode}: {r.stderr[-300:]})")
if r.returncode != 0:
    sys.exit(1)
h, A, g = 0.12, 0.024, 9.81
c_theory = np.sqrt(g * (h + A))
data = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
t = data["time"]


def crest(name):
    eta = data[name] - h
    k = int(np.argmax(eta))
    y0, y1, y2 = eta[k - 1], eta[k], eta[k + 1]
    dt = t[k + 1] - t[k]
    shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
    return t[k] + shift * dt, y1 - 0.25 * (y0 - y2) * shift


t5, a5 = crest("H_5h")
t10, a10 = crest("H_10h")
t12, a12 = crest("H_12h")
c_meas = (1.26 - 0.66) / (t10 - t5)
print(f"crest heights: {a5:.4f} m at 5h (t = {t5:.3f} s), {a10:.4f} m at 10h, {a12:.4f} m at 12h (A = {A} m)")
print(f"celerity between 5h and 10h: {c_meas:.4f} m/s, theory sqrt(g (h + A)) = {c_theory:.4f} m/s "
      f"({100 * (c_meas / c_theory - 1):+.2f} %)")
s = json.load(open(os.path.join(out, "summary.json")))
print("removed:", s["removed"], " in walls:", s["in_walls"])
check(abs(a5 - A) <= 0.10 * A, f"height at 5 depths {a5:.4f} m within 10 % of A = {A} m ({100 * (a5 / A - 1):+.1f} %)")
check(abs(c_meas / c_theory - 1) <= 0.03, f"celerity {c_meas:.4f} m/s within 3 % of {c_theory:.4f} m/s")
check(s["removed"]["total"] == 0 and s["in_walls"]["max_at_an_output"] == 0,
      "no water removed or found inside the paddle or the flume")
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    k = np.sqrt(3 * A / (4 * h ** 3))
    fig, ax = plt.subplots(figsize=(8, 3.5))
    for name, x, tc in (("H_5h", 0.66, t5), ("H_10h", 1.26, t10), ("H_12h", 1.50, t12)):
        ax.plot(t, (data[name] - h) / A, label=f"surge, x = {x} m")
        ax.plot(t, 1 / np.cosh(k * c_theory * (t - tc)) ** 2, "k:", lw=0.8)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("eta / A")
    ax.set_title("Piston solitary wave, A/h = 0.2, h = 12 dp (dotted: A sech^2 at the measured crest time)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(WORK, "solitary_piston.png"), dpi=110)
except ImportError:
    pass
print("FAILED: " + "; ".join(failures) if failures else "all passed")
sys.exit(1 if failures else 0)
