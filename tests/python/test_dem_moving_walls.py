"""DEM walls that move (issue 34), from case files:

1. DEM only: cases/boulder_on_gravel.yaml's free block thrown onto gravel lands on the bed
   (it does not pass through it: its centre stays above the bed's top plus half its
   height, less 30 % for the spheres' overlap and its tilt) and a restart across the
   impact continues bitwise (gauges, sphere frame, checkpoint with the body's state);
   thrown at 10 m/s it leaves the domain and the run stops (exit 3, naming it).
2. Coupled, a gate seen by water and spheres: an SPH gate lifted at 1 m/s from 0.05 s and
   a DEM mesh of the same box that `follows` it hold a pile of spheres in water; no sphere
   reaches beyond the gate while it is shut, some do after it lifts, and a restart while
   it rises continues bitwise.
3. Coupled, a free floating box (an SPH body) that a DEM mesh follows, spheres dropped on
   it: the spheres do not pass through it, they push it down (by 0.1 s at least half the
   way to the lower floating level their weight gives it) and a restart continues bitwise.

usage: test_dem_moving_walls.py SURGE CASES_DIR WORKDIR"""
import os
import shutil
import subprocess
import sys

import numpy as np

SURGE, CASES, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(*args):
    r = subprocess.run([SURGE, *args, "--quiet"], capture_output=True, text=True)
    return r


def restarted_bitwise(name, case, end, stop, files):
    """Runs `case` to `end` straight and stopped at `stop` then restarted; compares files.
    Returns the straight run's folder, or None."""
    a, b = os.path.join(WORK, name + "_straight"), os.path.join(WORK, name + "_restarted")
    ra = run("run", case, "--out", a, "--set", f"time.end={end}")
    rb = run("run", case, "--out", b, "--set", f"time.end={stop}")
    rc = run("restart", b, "--set", f"time.end={end}")
    ok = ra.returncode == rb.returncode == rc.returncode == 0
    check(ok, f"{name}: runs and restarts (exit {ra.returncode} {rb.returncode} {rc.returncode}: "
          f"{(ra.stderr + rb.stderr + rc.stderr)[-300:]})")
    if not ok:
        return None
    for f in files:
        same = open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read()
        check(same, f"{name} restarted at {stop} s: {f} bitwise identical to the straight run")
    return a


def box_stl(path, lo, hi):
    c = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    with open(path, "w") as f:
        f.write("solid box\n")
        for a, b, cc, d in faces:
            for tri in ((a, b, cc), (a, cc, d)):
                f.write(" facet normal 0 0 0\n  outer loop\n")
                for i in tri:
                    f.write("   vertex %.6f %.6f %.6f\n" % c[i])
                f.write("  endloop\n endfacet\n")
        f.write("endsolid box\n")


def spheres(folder, frame):
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(folder, "particles", "spheres_%04d.vtp" % frame))
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPoints().GetData())


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# 1. The block on gravel (DEM only).
for f in ("boulder_on_gravel.yaml", "boulder_block.stl"):
    shutil.copy(os.path.join(CASES, f), WORK)
out = restarted_bitwise("boulder", os.path.join(WORK, "boulder_on_gravel.yaml"), 0.12, 0.08,
                        ["gauges.csv", "particles/spheres_0006.vtp", "particles/dem_walls_0006.vtp", "checkpoint.bin"])
if out:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    landed = g["time"] > 0.08
    lowest = g["block_z"][landed].min()
    check(lowest > 0.03 + 0.7 * 0.02, f"the block lands on the gravel and stays on it (lowest centre "
          f"{lowest:.4f} m; bed top 0.03 m, half height 0.02 m)")
    check(g["block_fz"][landed].max() > 0, "the spheres push the block up once it has landed")
# Thrown at 10 m/s along the bed it leaves the domain through the front wall (bodies do
# not meet walls yet): the run stops there, exit 3 naming it, the outputs kept.
r = run("run", os.path.join(WORK, "boulder_on_gravel.yaml"), "--out", os.path.join(WORK, "boulder_thrown"),
        "--set", "time.end=0.2", "--set", "dem.walls.5.body.velocity=[10,0,0]")
g = np.genfromtxt(os.path.join(WORK, "boulder_thrown", "gauges.csv"), delimiter=",", names=True)
check(r.returncode == 3 and "the free body 'block' left the domain (x in" in r.stderr and g["time"][-1] < 0.2,
      f"a block thrown out of the domain stops the run, exit 3 naming it, gauges kept to {g['time'][-1]:.3f} s "
      f"(exit {r.returncode}: {r.stderr[-200:]})")

# 2. A gate lifted from a pile of spheres in water; the spheres see it through a DEM mesh.
GATE = """name: gate_spheres
dp: 0.01
time: {end: 0.2, output_every: 0.02, gauge_every: 0.005}
domain: {min: [0, 0, 0], max: [0.4, 0.06, 0.32]}
sph: {boundary: mdbc}
fluid:
  - box: {min: [0, 0, 0], max: [0.15, 0.06, 0.1]}
walls:
  - name: tank
    box: {min: [0, 0, 0], max: [0.4, 0.06, 0.32]}
    open: [zmax]
  - name: gate
    box: {min: [0.15, 0, 0], max: [0.17, 0.06, 0.14]}
    solid: true
    motion: {law: constant_velocity, velocity: [0, 0, 1.0], start: 0.05}
dem:
  materials:
    - {name: grains, density: 2600, E: 1.0e6, nu: 0.2, phi: 30, restitution: 0.5}
  walls:
    - {plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: grains}
    - {plane: {point: [0, 0, 0], normal: [1, 0, 0]}, material: grains}
    - {plane: {point: [0, 0, 0], normal: [0, 1, 0]}, material: grains}
    - {plane: {point: [0, 0.06, 0], normal: [0, -1, 0]}, material: grains}
    - {name: gate_dem, mesh: gate.stl, material: grains, follows: gate}
  packs:
    - {box: {min: [0.1, 0, 0], max: [0.15, 0.06, 0.05]}, radius: 0.005, material: grains}
gauges:
  - {name: gz, type: body, wall: gate, component: z}
"""
open(os.path.join(WORK, "gate.yaml"), "w").write(GATE)
box_stl(os.path.join(WORK, "gate.stl"), (0.15, 0, 0), (0.17, 0.06, 0.14))
out = restarted_bitwise("gate", os.path.join(WORK, "gate.yaml"), 0.2, 0.14,
                        ["gauges.csv", "particles/fluid_0010.vtp", "particles/spheres_0010.vtp",
                         "particles/dem_walls_0010.vtp", "checkpoint.bin"])
if out:
    shut = spheres(out, 2)  # t = 0.04 s: the gate has not moved yet
    check(shut[:, 0].max() < 0.15, f"no sphere passes the shut gate (largest x {shut[:, 0].max():.4f} m < 0.15)")
    import vtk
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(out, "particles", "dem_walls_0010.vtp"))
    r.Update()
    zmin = r.GetOutput().GetBounds()[4]
    check(r.GetOutput().GetNumberOfPolys() == 12 and abs(zmin - 0.15) < 1e-6,
          f"the frames show the DEM gate lifted with the SPH gate (12 triangles, bottom at {zmin:.6f} m = 0.15)")
    lifted = spheres(out, 10)  # t = 0.2 s: lifted by 15 cm, out of the way
    check((lifted[:, 0] > 0.17).sum() >= 10,
          f"spheres run out under the lifted gate ({(lifted[:, 0] > 0.17).sum()} of 150 beyond it at 0.2 s, >= 10)")

# 3. Spheres dropped onto a floating box (a free SPH body) that a DEM mesh follows.
FLOAT = """name: float_spheres
dp: 0.01
time: {end: 0.1, output_every: 0.02, gauge_every: 0.005}
domain: {min: [0, 0, 0], max: [0.2, 0.2, 0.25]}
sph: {boundary: mdbc}
fluid:
  - box: {min: [0, 0, 0], max: [0.2, 0.2, 0.12]}
walls:
  - name: tank
    box: {min: [0, 0, 0], max: [0.2, 0.2, 0.25]}
    open: [zmax]
  - name: box
    box: {min: [0.05, 0.05, 0.09], max: [0.15, 0.15, 0.15]}
    solid: true
    body: {density: 500}
dem:
  materials:
    - {name: grains, density: 2600, E: 1.0e6, nu: 0.2, phi: 30, restitution: 0.5}
  walls:
    - {name: box_dem, mesh: float.stl, material: grains, follows: box}
  packs:
    - {box: {min: [0.08, 0.08, 0.16], max: [0.12, 0.12, 0.18]}, radius: 0.005, material: grains,
       velocity: [0, 0, -1]}
gauges:
  - {name: vz, type: body, wall: box, component: vz}
  - {name: z, type: body, wall: box, component: z}
"""
open(os.path.join(WORK, "float.yaml"), "w").write(FLOAT)
box_stl(os.path.join(WORK, "float.stl"), (0.05, 0.05, 0.09), (0.15, 0.15, 0.15))
out = restarted_bitwise("float", os.path.join(WORK, "float.yaml"), 0.1, 0.06,
                        ["gauges.csv", "particles/spheres_0005.vtp", "checkpoint.bin"])
if out:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    top = g["z"][-1] + 0.03  # the box's top now (its centre of mass is mid-height)
    sp = spheres(out, 5)
    over = (np.abs(sp[:, 0] - 0.1) < 0.05) & (np.abs(sp[:, 1] - 0.1) < 0.05)
    check(sp[over, 2].min() > top, f"the spheres rest on the box (lowest centre {sp[over, 2].min():.4f} m above "
          f"its top {top:.4f} m)")
    # Their weight lowers the box's floating level by m / (rho A) (A = 0.01 m^2 of
    # waterline); by 0.1 s it is still on its way there and bobbing (its velocity at one
    # instant has either sign), so half of that drop is asked for.
    drop = over.sum() * 2600 * 4 / 3 * np.pi * 0.005 ** 3 / (1000 * 0.01)
    check(g["z"][0] - g["z"][-1] > drop / 2, f"the spheres push the floating box down ({1000 * (g['z'][0] - g['z'][-1]):.2f} "
          f"mm by 0.1 s; their weight's new floating level {1000 * drop:.2f} mm lower)")

print("FAILED: " + "; ".join(failures) if failures else "all passed")
sys.exit(1 if failures else 0)
