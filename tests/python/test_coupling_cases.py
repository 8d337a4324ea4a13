"""End-to-end checks of the SPH-DEM coupling through the program and its case files:
Archimedes on a fixed submerged sphere and a floating sphere (coarse end, D/6), a
neutrally buoyant sphere (D/12, small tank), bitwise restart of a coupled run, the
paper's resolution warnings in `surge check`, and clean rejection of a bad sphere gauge."""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

SURGE, WORK, CASES = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(args):
    return subprocess.run([SURGE] + args, capture_output=True, text=True)


# The sphere of archimedes.yaml and floating.yaml: R = 0.03 m; rho g V of its volume of water.
R_SPHERE = 0.03
RHO_G_V = 1000.0 * 9.81 * 4.0 / 3.0 * math.pi * R_SPHERE**3

shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# --- Archimedes at D/6 (cases/archimedes.yaml): a fixed sphere R = 0.03 m under 0.06 m of
# water. The vertical fluid force, averaged over t in [0.15, 0.3] s (after the start-up
# sloshing), must be rho g V(r_eff) with the effective surface r_eff between the sphere's
# surface and half a particle spacing outside it (the paper's "gap effect": boundary
# particles keep the water about a spacing away). At D/6, r_eff <= R + dp/2 allows up to
# +59 % on rho g V; r_eff >= R means the force is not below rho g V. The horizontal force
# must average out: |Fx| below 3 % of rho g V.
out = os.path.join(WORK, "arch6")
r = run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", out])
check(r.returncode == 0, "archimedes D/6 runs (exit %d: %s)" % (r.returncode, r.stderr[-300:]))
if r.returncode == 0:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    R, dp, fb = R_SPHERE, 0.01, RHO_G_V
    m = (g["time"] >= 0.15) & (g["time"] <= 0.3 + 1e-9)
    fz, fx = g["fz"][m].mean(), g["fx"][m].mean()
    r_eff = R * (fz / fb) ** (1.0 / 3.0)
    print("     Fz = %.4f N, rho g V = %.4f N, ratio %.3f, r_eff = R + %.2f dp" % (fz, fb, fz / fb, (r_eff - R) / dp))
    check(R <= r_eff <= R + 0.5 * dp, "buoyancy: effective surface within [R, R + dp/2]")
    check(abs(fx) < 0.03 * fb, "no net horizontal force (|Fx| = %.4f N)" % abs(fx))

# --- the same at D/6 with the modified dynamic boundary (sph.boundary: mdbc), which
# closes the gap: the vertical force must be rho g V within 5 % (the coarse
# criterion). mDBC's start-up transient (the water closing the gap) lasts about 0.4 s,
# so the mean is taken over 0.5-0.7 s. Measured 2026-11-30: +0.3 % (dynamic: +30 %).
out = os.path.join(WORK, "arch6_mdbc")
r = run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", out, "--set", "sph.boundary=mdbc",
         "--set", "time.end=0.7", "--set", "time.output_every=0.1"])
check(r.returncode == 0, "archimedes D/6 with mdbc runs (exit %d: %s)" % (r.returncode, r.stderr[-300:]))
if r.returncode == 0:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    m = (g["time"] >= 0.5) & (g["time"] <= 0.7 + 1e-9)
    fz, fx = g["fz"][m].mean(), g["fx"][m].mean()
    print("     mdbc: Fz = %.4f N, rho g V = %.4f N, ratio %.4f" % (fz, RHO_G_V, fz / RHO_G_V))
    check(abs(fz / RHO_G_V - 1) < 0.05, "mdbc buoyancy within 5 % of rho g V at D/6")
    check(abs(fx) < 0.03 * RHO_G_V, "mdbc: no net horizontal force (|Fx| = %.4f N)" % abs(fx))

# --- walls hold water in both Archimedes runs: no fluid inside the tank's walls at any
# output (the sphere is a body, not a wall: not counted). With mdbc a few particles splash
# out over the open top (z > 0.2 m) in the start-up transient: printed, not a leak.
for name in ["arch6", "arch6_mdbc"]:
    sp = os.path.join(WORK, name, "summary.json")
    if os.path.exists(sp):
        s = json.load(open(sp))
        print("     %s: removed %s" % (name, s["removed"]))
        check(s["in_walls"]["max_at_an_output"] == 0, "%s: no water inside the walls (%s)" % (name, s["in_walls"]))

# --- a floating sphere (cases/floating.yaml, density 500) at D/6: it must float with its
# displaced volume (geometric, from its draught) between the values for an effective
# surface at R (exactly V/2) and at R + dp/2 (the gap effect bound used above), averaged
# over 0.5-1 s; 0.02 V allowed on top for the remaining heave.
def cap(d, r):
    d = min(max(d, 0.0), 2 * r)
    return math.pi * d * d * (3 * r - d) / 3


def displaced_for_effective_radius(re, r, half):
    lo, hi = 0.0, 2 * re  # draught of the effective sphere holding `half` below the surface
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if cap(mid, re) < half else (lo, mid)
    return cap(lo - (re - r), r)


out = os.path.join(WORK, "float6")
r = run(["run", os.path.join(CASES, "floating.yaml"), "--out", out, "--quiet"])
check(r.returncode == 0, "floating D/6 runs (%s)" % r.stderr[-300:])
if r.returncode == 0:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    R, dp = 0.03, 0.01
    V = 4 / 3 * math.pi * R**3
    m = g["time"] >= 0.5
    ratio = np.mean([cap(s - (z - R), R) for s, z in zip(g["surface"][m], g["z"][m])]) / V
    low = displaced_for_effective_radius(R + dp / 2, R, V / 2) / V
    print("     displaced volume %.3f V (bounds %.3f .. 0.52)" % (ratio, low))
    check(low <= ratio <= 0.52, "floating sphere: displaced volume within the gap-effect bounds")

# --- a neutrally buoyant sphere (density 1000) at D/12 in still water must drift less than
# 0.1 D in 1 s (the criterion). cases/archimedes.yaml made smaller for CI: tank
# 0.12 m, water 0.12 m deep, the sphere's centre at mid-depth, free, dp = 5 mm = D/12
# (at D/6 the gap effect adds 27 % to the buoyancy, so a density-1000 sphere rises there).
# The mean fluid force over 0.2-1 s must also balance the weight within 3 %.
out = os.path.join(WORK, "neutral12")
r = run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", out, "--quiet", "--set", "dp=0.005",
         "--set", "domain.max=[0.12,0.12,0.14]", "--set", "fluid.0.box.max=[0.12,0.12,0.12]",
         "--set", "walls.0.box.max=[0.12,0.12,0.14]", "--set", "dem.packs.0.box.min=[0.03,0.03,0.03]",
         "--set", "dem.packs.0.box.max=[0.09,0.09,0.09]", "--set", "dem.packs.0.fixed=false",
         "--set", "dem.materials.0.density=1000", "--set", "time.end=1", "--set", "time.output_every=0.5",
         "--set", "gauges.1.name=z", "--set", "gauges.1.component=z"])
check(r.returncode == 0, "neutral sphere D/12 runs (%s)" % r.stderr[-300:])
if r.returncode == 0:
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    D, weight = 2 * R_SPHERE, RHO_G_V  # density 1000: its weight is the water's rho g V
    drift = np.abs(g["z"] - g["z"][0]).max()
    fz = g["fz"][g["time"] >= 0.2].mean()
    print("     largest drift %.2f mm = %.3f D; mean fluid force %.4f N, weight %.4f N" % (drift * 1e3, drift / D, fz,
                                                                                          weight))
    check(drift < 0.1 * D, "neutral sphere: drift below 0.1 D in 1 s")
    check(abs(fz - weight) < 0.03 * weight, "neutral sphere: fluid force balances the weight within 3 %")

# --- restart of a coupled run (a sinking sphere): stopped at 0.02 s and continued to 0.04 s
# it ends bitwise identical to the straight run (water, spheres, gauges), with either
# boundary. (The sphere sinks almost without turning, so with mdbc this does not prove
# that the body particles' ghost nodes are re-placed from the restored orientation.)
for bc in ["dynamic", "mdbc"]:
    sink = ["--set", "dem.packs.0.fixed=false", "--set", "time.output_every=0.02", "--set", "time.gauge_every=0.005",
            "--set", "sph.boundary=" + bc, "--quiet"]
    out_a, out_b = os.path.join(WORK, "sink_straight_" + bc), os.path.join(WORK, "sink_restarted_" + bc)
    run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", out_a, "--set", "time.end=0.04"] + sink)
    run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", out_b, "--set", "time.end=0.02"] + sink)
    r = run(["restart", out_b, "--set", "time.end=0.04"])
    check(r.returncode == 0, "coupled restart (%s) runs (%s)" % (bc, r.stderr[-300:]))
    for name in ["particles/fluid_0002.vtp", "particles/spheres_0002.vtp", "gauges.csv"]:
        pa, pb = os.path.join(out_a, name), os.path.join(out_b, name)
        same = os.path.exists(pa) and os.path.exists(pb) and open(pa, "rb").read() == open(pb, "rb").read()
        check(same, "coupled restart (%s): %s bitwise identical" % (bc, name))
    ga = np.genfromtxt(os.path.join(out_a, "gauges.csv"), delimiter=",", names=True)
    check(ga["fz"][-1] != 0 and np.all(np.diff(ga["fz"][1:]) != 0), "the sphere moved and felt the water (%s)" % bc)

# --- resolution warnings (paper sect. 4): loose spheres want dp <= D/20, dense ones D/6
r = run(["check", os.path.join(CASES, "water_entry.yaml")])
check(r.returncode == 0 and "dp <= D/20" in r.stdout, "water entry at D/6 warns: loose spheres want D/20")
r = run(["check", os.path.join(CASES, "water_entry.yaml"), "--set", "dp=0.00127"])
check(r.returncode == 0 and "D/20" not in r.stdout, "water entry at D/20: no sphere resolution warning")
r = run(["check", os.path.join(CASES, "floating.yaml"), "--set", "dp=0.003"])  # D = 0.06 is not exact in float
check(r.returncode == 0 and "D/20" not in r.stdout, "floating sphere at D/20: no sphere resolution warning")
r = run(["check", os.path.join(CASES, "slide_tsunami.yaml")])
check(r.returncode == 0 and "dense assembly" in r.stdout and "D/6" in r.stdout, "slide at D/4 warns: dense wants D/6")
check("spheres     522" in r.stdout, "slide: 522 spheres")
check("gap at the spheres raises the slide's wave" in r.stdout, "slide with the dynamic boundary: the gap is named")
r = run(["check", os.path.join(CASES, "slide_tsunami.yaml"), "--set", "sph.boundary=mdbc"])
check(r.returncode == 0 and "dense assembly" in r.stdout and "gap at the spheres" not in r.stdout,
      "slide with mdbc: the resolution warning without the gap")

# --- a sphere gauge naming a sphere that does not exist: exit 2, message with the line,
# nothing written
bad_out = os.path.join(WORK, "bad")
r = run(["run", os.path.join(CASES, "archimedes.yaml"), "--out", bad_out, "--set", "gauges.0.sphere=3"])
check(r.returncode == 2, "bad sphere gauge: exit 2 (got %d)" % r.returncode)
check("archimedes.yaml" in r.stderr and "sphere 3 does not exist" in r.stderr, "bad sphere gauge: clear message")
check(not os.path.exists(bad_out), "bad sphere gauge: nothing written")

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
