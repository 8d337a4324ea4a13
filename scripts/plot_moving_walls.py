#!/usr/bin/env python3
"""Figures of issue 34's validation runs (docs/validation.md, "Walls that move").

  plot_moving_walls.py front NOGATE_DIR GATE_DIR DATA_DIR OUT.png   dam break I front with and without the gate
  plot_moving_walls.py solitary RUN_DIR OUT.png                     the piston's solitary wave at its gauges
  plot_moving_walls.py floating BOX_DIR CUBE_DIR OUT.png            the floating box and cube: draft and tilt
  plot_moving_walls.py slide RUN_DIR OUT.png                        the rigid wedge: its speed and the waves
  plot_moving_walls.py boulder RUN_DIR OUT.png                      the block on gravel (DEM walls that move)

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


def floating(box, cube, out):
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    for d, lab in ((box, "box 0.2 x 0.2 x 0.1 m"), (cube, "cube 0.1 m")):
        g = np.genfromtxt(os.path.join(d, "gauges.csv"), delimiter=",", names=True)
        ax.plot(g["time"], (g["level"] - (g["z"] - 0.05)) / 0.05, label=lab)
        bx.plot(g["time"], g["tilt"], label=lab)
    ax.axhline(1, color="k", lw=0.6, ls=":")
    ax.set_ylabel("draft / (H/2)")
    ax.set_ylim(0.9, 1.1)
    ax.legend(fontsize=8)
    ax.set_title("Free bodies of density 500, kicked by 0.5 rad/s about x (mdbc, dp = 1 cm)")
    bx.set_ylabel("tilt [degrees]")
    bx.set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def slide(run, out):
    g = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    speed = g["wedge_vx"] / np.cos(np.radians(35))
    ax.plot(g["time"], speed, "k", label="wedge speed along the slope")
    a = 9.81 * (np.sin(np.radians(35)) - 0.3 * np.cos(np.radians(35)))
    ax.plot(g["time"], np.minimum(a * g["time"], speed.max() * 1.5), "k:", lw=0.8, label="g (sin - mu_k cos) t, dry")
    ax.set_ylabel("m/s")
    ax.legend(fontsize=8)
    ax.set_title("Rigid wedge, 35-degree slope, water 0.3 m deep (mdbc, dp = 12.5 mm)")
    for name, x in (("H_09", 0.9), ("H_12", 1.2), ("H_15", 1.5)):
        bx.plot(g["time"], g[name] - 0.3, label=f"x = {x} m")
    bx.set_ylabel("eta [m]")
    bx.set_xlabel("t [s]")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def boulder(run, out):
    g = np.genfromtxt(os.path.join(run, "gauges.csv"), delimiter=",", names=True)
    fig, (ax, bx, cx) = plt.subplots(3, 1, figsize=(7, 6.5), sharex=True)
    ax.plot(g["time"], g["block_x"], "k", label="x of the centre")
    ax.plot(g["time"], g["block_z"], "b", label="z of the centre")
    ax.axhline(0.03 + 0.02, color="b", ls=":", lw=0.8, label="resting on the bed top (0.03 m + half height)")
    ax.set_ylabel("m")
    ax.legend(fontsize=8)
    ax.set_title("Block (0.24 kg) thrown onto gravel (2,880 spheres of r = 5 mm), DEM only")
    bx.plot(g["time"], g["block_vx"], "k", label="vx")
    bx.plot(g["time"], g["block_vz"], "b", label="vz")
    bx.set_ylabel("m/s")
    bx.legend(fontsize=8)
    weight = 2500 * 0.06 * 0.04 * 0.04 * 9.81
    cx.plot(g["time"], g["block_fz"], "k", lw=0.8, label="fz of the spheres on the block")
    cx.axhline(weight, color="r", ls=":", label=f"its weight, {weight:.3f} N")
    cx.set_ylim(-1, 4 * weight)
    cx.set_ylabel("N")
    cx.set_xlabel("t [s]")
    cx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    {"front": front, "solitary": solitary, "floating": floating, "slide": slide,
     "boulder": boulder}[sys.argv[1]](*sys.argv[2:])
