"""SPHERIC test 2: the height gauges' NRMSE as issue 35 defines it (rms error over
(0.05, 6] s, the measurement interpolated to the run's gauge times, over the largest
measured height) and the box-front plateau (0.5-0.8 s means of P1-P4 against the measured
4.59 / 4.33 / 4.13 / 3.56 kPa), for each run folder given. The data file's H1 and H3
columns are swapped (data/README.md).

usage: spheric_nrmse.py RUN_DIR... [--data data]"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import surge_post  # noqa: E402

args = sys.argv[1:]
data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
if "--data" in args:
    k = args.index("--data")
    data = args[k + 1]
    del args[k:k + 2]
exp = np.loadtxt(os.path.join(data, "spheric_test2_kleefsman_exp.dat"), skiprows=2)
cols = {"H3": 9, "H2": 10, "H1": 11, "H4": 12}
window = (exp[:, 0] > 0.05) & (exp[:, 0] <= 6.0)
measured = [4.59, 4.33, 4.13, 3.56]
for run in args:
    names, sim = surge_post.read_gauges(os.path.join(run, "gauges.csv"))
    t = sim[:, 0]
    m = (t > 0.05) & (t <= 6.0)
    nrmse = []
    for g in ("H1", "H2", "H3", "H4"):
        e = np.interp(t[m], exp[:, 0], exp[:, cols[g]])
        nrmse.append(np.sqrt(np.mean((sim[m, names.index(g)] - e) ** 2)) / exp[window, cols[g]].max())
    plateau = (t >= 0.5) & (t <= 0.8)
    p = [sim[plateau, names.index("P%d" % k)].mean() / 1000 for k in range(1, 5)]
    print(f"{run}: NRMSE H1-H4 " + " / ".join("%.3f" % x for x in nrmse) + " | plateau P1-P4 " +
          " / ".join("%.2f kPa (%+.0f %%)" % (a, 100 * (a / b - 1)) for a, b in zip(p, measured)))
