"""SPHERIC test 2: the height gauges' NRMSE as issue 35 defines it (rms error over
(0.05, END] s, END = 6 unless --end, the measurement interpolated to the run's gauge
times, over the largest measured height) and the box-front plateau (0.5-0.8 s means of
P1-P4 against the measured 4.59 / 4.33 / 4.13 / 3.56 kPa), for each run folder given.
The data file's H1 and H3 columns are swapped (data/README.md).

A plateau mean comes with its standard error from six 0.05-s block means: the SPH
pressures carry acoustic noise whose standard deviation is of the order of the mean
itself, and the samples within a block are correlated, so the naive error of 61 samples
would understate it.

usage: spheric_nrmse.py RUN_DIR... [--data data] [--end 1.5]"""
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
end = 6.0
if "--end" in args:
    k = args.index("--end")
    end = float(args[k + 1])
    del args[k:k + 2]
exp = np.loadtxt(os.path.join(data, "spheric_test2_kleefsman_exp.dat"), skiprows=2)
cols = {"H3": 9, "H2": 10, "H1": 11, "H4": 12}
window = (exp[:, 0] > 0.05) & (exp[:, 0] <= end)
measured = [4.59, 4.33, 4.13, 3.56]
for run in args:
    names, sim = surge_post.read_gauges(os.path.join(run, "gauges.csv"))
    t = sim[:, 0]
    m = (t > 0.05) & (t <= end)
    nrmse = []
    for g in ("H1", "H2", "H3", "H4"):
        e = np.interp(t[m], exp[:, 0], exp[:, cols[g]])
        nrmse.append(np.sqrt(np.mean((sim[m, names.index(g)] - e) ** 2)) / exp[window, cols[g]].max())
    plateau = []
    for k in range(1, 5):
        blocks = [b.mean() for b in np.array_split(sim[(t >= 0.5) & (t <= 0.8), names.index("P%d" % k)], 6)]
        plateau.append((np.mean(blocks) / 1000, np.std(blocks, ddof=1) / np.sqrt(len(blocks)) / 1000))
    print(f"{run}: NRMSE H1-H4 (0.05-{end:g} s) " + " / ".join("%.3f" % x for x in nrmse) + " | plateau P1-P4 " +
          " / ".join("%.2f+-%.2f kPa (%+.0f %%)" % (a, e, 100 * (a / b - 1)) for (a, e), b in zip(plateau, measured)))
