"""Walls that move (issue 34): a solid block driven through still water at a constant
velocity, with either wall model, at 0.5 m/s and (with the no-penetration condition, on
by default) at 2 m/s. At every output no fluid particle may be inside the block where it
is then, or inside the tank (summary.json in_walls, counted from the walls' geometry in
the block's own frame), none may be removed, and the block's body gauge must follow the
law (x = x0 + v t) and feel a drag against its motion.

usage: test_moving_walls.py SURGE WORKDIR [--quick | --long]
  --quick (quick tests): mdbc at 0.5 m/s for 0.1 s, the restarts of a flap and a free block, and a
  free block that sinks out of the domain (the run stops, exit 3);
  default (CI's validation, about 2 minutes): the dynamic boundary at 0.5 m/s for 0.15 s and both
  models at 2 m/s for 0.1 s; --long (ctest -L long): both models at 0.5 m/s for 0.3 s (the drag
  coefficients of docs/validation.md) and at 2 m/s, and the restarts."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

SURGE, WORK = sys.argv[1], sys.argv[2]
QUICK = "--quick" in sys.argv
LONG = "--long" in sys.argv
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


CASE = """name: moving_block
dp: 0.01
time: {{end: {end}, output_every: 0.01, gauge_every: 0.005}}
domain: {{min: [0, 0, 0], max: [0.6, 0.12, 0.3]}}
sph: {{boundary: {boundary}}}
fluid:
  - box: {{min: [0, 0, 0], max: [0.6, 0.12, 0.2]}}
walls:
  - name: tank
    box: {{min: [0, 0, 0], max: [0.6, 0.12, 0.3]}}
    open: [zmax]
  - name: block
    box: {{min: [0.1, 0.04, 0.06], max: [0.14, 0.08, 0.14]}}
    solid: true
    motion: {{law: constant_velocity, velocity: [{v}, 0, 0]}}
gauges:
  - {{name: bx, type: body, wall: block, component: x}}
  - {{name: bvx, type: body, wall: block, component: vx}}
  - {{name: bfx, type: body, wall: block, component: fx}}
"""

shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
if QUICK:
    runs = [("mdbc", 0.5, 0.1)]
elif LONG:
    runs = [("dynamic", 0.5, 0.3), ("mdbc", 0.5, 0.3), ("dynamic", 2.0, 0.1), ("mdbc", 2.0, 0.1)]
else:
    runs = [("dynamic", 0.5, 0.15), ("dynamic", 2.0, 0.1), ("mdbc", 2.0, 0.1)]
for boundary, v, end in runs:
    name = f"{boundary}_{v}"
    path = os.path.join(WORK, name + ".yaml")
    open(path, "w").write(CASE.format(end=end, boundary=boundary, v=v))
    out = os.path.join(WORK, name)
    r = subprocess.run([SURGE, "run", path, "--out", out, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 0, f"{name}: the block moves through the water to t = {end} s (exit {r.returncode}: "
          f"{r.stderr[-300:]})")
    if r.returncode != 0:
        continue
    s = json.load(open(os.path.join(out, "summary.json")))
    print(f"     removed: {s['removed']}  in walls: {s['in_walls']}")
    check(s["in_walls"]["max_at_an_output"] == 0, f"{name}: no fluid inside the block or the tank at any output")
    check(s["removed"]["total"] == 0, f"{name}: no fluid particle removed")
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    moving = g["time"] > 0
    err = np.abs(g["bx"][moving] - (0.12 + v * g["time"][moving])).max()
    check(err < 2e-6, f"{name}: the pivot follows x = 0.12 + {v} t (largest difference {err:.2e} m)")
    check(np.all(np.abs(g["bvx"][moving] - v) < 1e-6), f"{name}: its velocity is {v} m/s")
    # Steady drag F = Cd rho A v^2 / 2 with A = 0.04 x 0.08 m^2 after the start (t > 0.05 s;
    # the first instants carry the impulsive start's added-mass force).
    late = g["time"] > min(0.05, end / 2)
    fx = g["bfx"][late].mean()
    cd = -fx / (0.5 * 1000 * 0.04 * 0.08 * v * v)
    print(f"     mean fx over t > {min(0.05, end / 2)} s: {fx:.3f} N, drag coefficient {cd:.2f}")
    check(fx < 0, f"{name}: the water holds the block back (mean fx {fx:.3f} N < 0)")


def restarted_bitwise(name, text, boundary):
    """Runs `text` to 0.06 s straight and stopped at 0.03 s then restarted; checks that
    gauges, fluid and wall frames and checkpoint are the same bits. Returns the straight
    run's folder, or None if a run failed."""
    path = os.path.join(WORK, name + ".yaml")
    open(path, "w").write(text.format(end=0.06, boundary=boundary, v=0))
    a, b = os.path.join(WORK, name + "_straight"), os.path.join(WORK, name + "_restarted")
    ra = subprocess.run([SURGE, "run", path, "--out", a, "--quiet"], capture_output=True, text=True)
    rb = subprocess.run([SURGE, "run", path, "--out", b, "--quiet", "--set", "time.end=0.03"], capture_output=True,
                        text=True)
    rc = subprocess.run([SURGE, "restart", b, "--set", "time.end=0.06", "--quiet"], capture_output=True, text=True)
    check(ra.returncode == rb.returncode == rc.returncode == 0, f"the {name} runs and restarts ({rc.stderr[-200:]})")
    if rc.returncode != 0:
        return None
    for f in ("gauges.csv", "particles/fluid_0006.vtp", "particles/walls_0006.vtp", "checkpoint.bin"):
        same = open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read()
        check(same, f"{name} restarted at 0.03 s: {f} bitwise identical to the straight run")
    return a


# A restart continues a moving wall bitwise: a flap turning about its hinge (sinusoidal,
# 15 degrees, dynamic boundary: its no-penetration faces turn with it).
BLOCK = ("  - name: block\n    box: {{min: [0.1, 0.04, 0.06], max: [0.14, 0.08, 0.14]}}\n    solid: true\n"
         "    motion: {{law: constant_velocity, velocity: [{v}, 0, 0]}}\n")
FLAP = CASE.replace(BLOCK, "  - name: block\n    box: {{min: [0.1, 0, 0], max: [0.13, 0.12, 0.25]}}\n    solid: true\n"
                    "    motion: {{law: sinusoidal, period: 0.5, angle: 15, axis: [0, 1, 0], pivot: [0.115, 0.06, 0]}}\n")
FLAP = FLAP.replace("bx, type: body, wall: block, component: x", "bmy, type: body, wall: block, component: my")
FLAP = FLAP.replace("bvx, type: body, wall: block, component: vx", "bvz, type: body, wall: block, component: vz")
assert FLAP != CASE
if not (QUICK or LONG):  # the restarts are the quick tests' (and the long run's)
    print("FAILED: " + "; ".join(failures) if failures else "all passed")
    sys.exit(1 if failures else 0)
out = restarted_bitwise("flap", FLAP, "dynamic")
if out:
    s = json.load(open(os.path.join(out, "summary.json")))
    check(s["in_walls"]["max_at_an_output"] == 0 and s["removed"]["total"] == 0,
          f"flap: no fluid inside a wall or removed ({s['in_walls']}, removed {s['removed']['total']})")

# A free body restarts bitwise too (its state rides in the checkpoint): the block, density
# 700, let go in the water (it rises).
FREE = CASE.replace(BLOCK, BLOCK.split("    motion:")[0] + "    body: {{density: 700}}\n")
FREE = FREE.replace("bvx, type: body, wall: block, component: vx", "bvz, type: body, wall: block, component: vz")
assert FREE != CASE
out = restarted_bitwise("free block", FREE, "mdbc")
if out:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    check(g["bvz"][-1] > 0, f"the free block (density 700) rises (vz = {g['bvz'][-1]:.4f} m/s at 0.06 s)")

# A free body that leaves the domain stops the run (bodies do not meet walls yet: a block
# of density 8000 sinks through the tank's floor), exit 3 naming it, the outputs kept.
path = os.path.join(WORK, "sinking.yaml")
open(path, "w").write(FREE.replace("density: 700", "density: 8000").format(end=0.5, boundary="mdbc", v=0))
out = os.path.join(WORK, "sinking")
r = subprocess.run([SURGE, "check", path, "--set", "dp=0.02"], capture_output=True, text=True)
check("warning     the free body 'block' (8000 kg/m^3) is denser than the water" in r.stdout,
      "surge check warns that the free block will sink through the floor")
r = subprocess.run([SURGE, "run", path, "--out", out, "--quiet", "--set", "dp=0.02"], capture_output=True, text=True)
s = json.load(open(os.path.join(out, "summary.json")))
check(r.returncode == 3 and "the free body 'block' left the domain (z in" in r.stderr and s["status"] == "diverged",
      f"a sinking free block stops the run, exit 3 naming it (exit {r.returncode}: {r.stderr[-300:]})")
g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
check(0 < g["time"][-1] < 0.5 and os.path.exists(os.path.join(out, "particles", "fluid_0001.vtp")),
      f"its gauges (to {g['time'][-1]:.3f} s) and frames up to then are kept")

print("FAILED: " + "; ".join(failures) if failures else "all passed")
sys.exit(1 if failures else 0)
