#!/usr/bin/env python3
"""Figures of issue 34's validation runs (docs/validation.md, "Walls that move").

  plot_moving_walls.py front NOGATE_DIR GATE_DIR DATA_DIR OUT.png   dam break I front with and without the gate
  plot_moving_walls.py solitary RUN_DIR OUT.png                     the piston's solitary wave at its gauges

NOGATE_DIR and GATE_DIR are the output folders of tests/python/test_dambreak_front.py
(without and with `gate`), RUN_DIR that of cases/solitary_piston.yaml."""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import surge_post  # noqa: E402


def front(nogate, gate, data_dir, out):
    a = 0.146
    dp = a / 12
    exp = np.array(surge_post.read_front_data(os.path.join(data_dir, "koshizuka_oka_1996_front.txt")))
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(exp[:, 0], exp[:, 1], "ko", label="Koshizuka & Oka (1996)")
    for d, lab in ((nogate, "surge, column released at once"), (gate, "surge, gate lifted at 1.2 m/s")):
        pts = [(t, surge_post.surge_front(surge_post.read_vtp(f)["position"], dp))
               for t, f in surge_post.read_pvd(os.path.join(d, "fluid.pvd"))]
        t, x = np.array(pts).T
        ax.plot(t * np.sqrt(2 * 9.81 / a), x / a, label=lab)
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = front / a")
    ax.set_xlim(0, 3.3)
    ax.set_ylim(1, 4.1)
    ax.set_title("Dam break I, dp = a/12: the gate")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def solitary(run, out):
    h, A = 0.12, 0.024
    g = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    for name, x in (("H_5h", 0.66), ("H_10h", 1.26), ("H_12h", 1.50)):
        ax.plot(g["time"], (g[name] - h) / A, label=f"x = {x} m")
    ax.axhline(1, color="k", lw=0.6, ls=":")
    ax.set_ylabel("eta / A")
    ax.legend(fontsize=8)
    ax.set_title("Piston solitary wave, A/h = 0.2, h = 12 dp, mdbc")
    bx.plot(g["time"], g["paddle_x"] - 0.04, "k")
    bx.set_ylabel("paddle [m]")
    bx.set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    if sys.argv[1] == "front":
        front(*sys.argv[2:6])
    else:
        solitary(*sys.argv[2:4])
