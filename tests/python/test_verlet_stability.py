#!/usr/bin/env python3
"""The Verlet scheme with density diffusion stays stable (issue 35's removals).

Leapfrog (rho+ = rho- + 2 dt D) applied to a diffusion term has a computational mode
that grows by about (1 + dt lam) per step, lam the term's decay rate; the Euler step
every `sph.euler_every` steps resets the two sequences and leaves (dt lam)^2 / 2 of it.
The mode dies where (dt lam)^2 / 2 (1 + dt lam)^N < 1: dt lam below about 0.14 for
N = 40, 0.35 for N = 10. For the lattice's checkerboard density (the fastest mode) the
Molteni term with delta = 0.1, h = 1.2 dp and dt = CFL h / c0 gives dt lam = 0.65 CFL:
0.13 at the default CFL 0.2, at the edge for N = 40 (docs/validation.md).

Here: a periodic cube of water at rest, no gravity, its density a +-0.1 % checkerboard
(the pressure forces cancel by symmetry: only the diffusion acts), CFL 0.25 (dt lam
about 0.16). With the default Euler interval the checkerboard decays to rounding; with
euler_every = 40 (the deliberately broken variant, the old default) it grows.

Usage: test_verlet_stability.py SURGE WORK"""
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import Checks  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import surge_post  # noqa: E402

SURGE, WORK = sys.argv[1], sys.argv[2]
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
checks = Checks(SURGE, WORK)
DP, N, EPS = 0.01, 10, 1e-3

i, j, k = np.meshgrid(np.arange(N), np.arange(N), np.arange(N), indexing="ij")
pos = np.column_stack([(i.ravel() + 0.5) * DP, (j.ravel() + 0.5) * DP, (k.ravel() + 0.5) * DP])
rho = 1000.0 * (1 + EPS * (-1.0) ** (i + j + k).ravel())
table = os.path.join(WORK, "checkerboard.csv")
np.savetxt(table, np.column_stack([pos, np.zeros_like(pos), rho]), fmt="%.9g", delimiter=",",
           header="x,y,z,vx,vy,vz,rho", comments="")


def case(name, extra):
    L = N * DP
    return f"""name: {name}
dp: {DP}
time: {{end: 0.6, output_every: 0.1}}
gravity: [0, 0, 0]
domain: {{min: [0, 0, 0], max: [{L}, {L}, {L}], periodic: [xmin, xmax, ymin, ymax, zmin, zmax]}}
sph: {{c0: 10, cfl: 0.25, integrator: verlet, hydrostatic_init: false{extra}}}
fluid: [{{particles: {table}}}]
"""


def last_deviation(out):
    """The largest |rho / rho0 - 1| of the last frame, and what was removed."""
    frames = surge_post.read_pvd(os.path.join(out, "fluid.pvd"))
    d = surge_post.read_vtp(frames[-1][1])["density"].astype(np.float64)
    s = surge_post.read_summary(os.path.join(out, "summary.json"))
    return np.abs(d / 1000.0 - 1).max(), s["removed"]["total"], s["steps"]


dev, removed, steps = last_deviation(checks.run("default", case("default", "")))
print(f"  default euler_every: |rho/rho0 - 1| {dev:.2e} after {steps} steps (from {EPS:g}), {removed} removed")
checks.check(dev < EPS / 100 and removed == 0,
             f"the checkerboard decays with the default Euler interval ({dev:.2e} < {EPS / 100:g}, none removed)")

out = os.path.join(WORK, "every40")
with open(out + ".yaml", "w") as f:
    f.write(case("every40", ", euler_every: 40"))
r = __import__("subprocess").run([SURGE, "run", out + ".yaml", "--out", out, "--quiet"], capture_output=True, text=True)
dev40, removed40, steps40 = last_deviation(out)
print(f"  euler_every 40: |rho/rho0 - 1| {dev40:.2e} after {steps40} steps, {removed40} removed (exit {r.returncode})")
checks.check(dev40 > EPS or removed40 > 0 or r.returncode != 0,
             "with euler_every 40 (the old default) it grows: the check can fail")
checks.finish("Verlet stability")
