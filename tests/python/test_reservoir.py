"""The real-site chain on the synthetic reservoir (cases/reservoir): grids written by
scripts/make_reservoir_case.py -> terrain, lake, slide -> hazard maps, checked against
properties that must hold:

* the water placed is within 2 % of the integral of level - terrain over the lake
  connected to the seed (computed here on a 0.5 m grid from the same triangulated surface);
  the closed basin on the north flank holds none;
* the slide's volume is the integral of the grids' difference (1 %) and its spheres' lattice
  cells hold it within 2 % (so its mass is that volume x the packing's solid share x density);
* before the wave arrives, the maximum-elevation map is the still level wherever it is wet
  (within dp/8), far from the slide as near it;
* a run restarted from its checkpoint writes the same maps, bit for bit, as a straight run;
* by 9 s, the water has risen above the still level near the slide and the run-up on the
  far (south) shore (the wave reaches it after 7 s) stands above the still level;
* bad input: crossed slide surfaces, a seed on dry land, a level above the domain, a file
  that is not a raster: exit 2 naming the file, nothing written.

usage: test_reservoir.py SURGE WORK SOURCE_DIR   (about 5 minutes on 2 cores)"""
import collections
import csv
import filecmp
import os
import re
import shutil
import subprocess
import sys

import numpy as np
from osgeo import gdal

SURGE, WORK, SRC = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def surge(*args, timeout=900):
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    return subprocess.run([SURGE, *args], capture_output=True, text=True, timeout=timeout, env=env)


def grid(path):
    ds = gdal.Open(path)
    z = ds.GetRasterBand(1).ReadAsArray().astype(float)[::-1, :]  # rows from the south
    gt = ds.GetGeoTransform()
    return z, gt[0] + gt[1] / 2, gt[3] + (z.shape[0] - 0.5) * gt[5], gt[1]


def surface(z, x0, y0, d, x, y):
    """The surface through the nodes, two triangles per square split along (i,j)-(i+1,j+1),
    as surge triangulates it."""
    u, w = (x - x0) / d, (y - y0) / d
    i = np.clip(np.floor(u).astype(int), 0, z.shape[1] - 2)
    j = np.clip(np.floor(w).astype(int), 0, z.shape[0] - 2)
    s, t = u - i, w - j
    z00, z10, z01, z11 = z[j, i], z[j, i + 1], z[j + 1, i], z[j + 1, i + 1]
    return np.where(s >= t, z00 + s * (z10 - z00) + t * (z11 - z10), z00 + t * (z01 - z00) + s * (z11 - z01))


shutil.rmtree(WORK, ignore_errors=True)
site = os.path.join(WORK, "site")
os.makedirs(site)
r = subprocess.run([sys.executable, os.path.join(SRC, "scripts", "make_reservoir_case.py"), site],
                   capture_output=True, text=True)
check(r.returncode == 0, "make_reservoir_case.py writes the grids " + r.stderr[-200:])
case = os.path.join(site, "reservoir.yaml")
shutil.copy(os.path.join(SRC, "cases", "reservoir", "reservoir.yaml"), case)
level, seed, dp = 1022.0, (600300.0, 5100075.0), 2.0

# --- surge check: the water and the slide against integrals of the grids
r = surge("check", case)
check(r.returncode == 0, "surge check passes " + r.stderr[-300:])
placed = float(re.search(r"water\s+([0-9.e+]+) m\^3 placed", r.stdout).group(1))
m = re.search(r"slide .*: ([0-9.e+]+) m\^3 between the grids; (\d+) spheres of D = ([0-9.]+) m whose lattice cells "
              r"hold ([0-9.e+]+) m\^3", r.stdout)
slide_volume, n_spheres, D, cells = float(m.group(1)), int(m.group(2)), float(m.group(3)), float(m.group(4))

z, x0, y0, d = grid(os.path.join(site, "pre_failure.tif"))
zb, _, _, _ = grid(os.path.join(site, "sliding_surface.tif"))
h = 0.5
xs = np.arange(600000 + h / 2, 600400, h)
ys = np.arange(5100000 + h / 2, 5100200, h)
X, Y = np.meshgrid(xs, ys)
ground = surface(zb, x0, y0, d, X, Y)  # the walls: the ground beneath the slide
water = ground < level
lake = np.zeros_like(water)  # the water connected to the seed, 4-neighbour flood fill
start = (int((seed[1] - 5100000) / h), int((seed[0] - 600000) / h))
queue = collections.deque([start])
lake[start] = True
while queue:
    j, i = queue.popleft()
    for jj, ii in ((j - 1, i), (j + 1, i), (j, i - 1), (j, i + 1)):
        if 0 <= jj < lake.shape[0] and 0 <= ii < lake.shape[1] and water[jj, ii] and not lake[jj, ii]:
            lake[jj, ii] = True
            queue.append((jj, ii))
lake_volume = float(np.sum((level - ground)[lake]) * h * h)
basin = water & ~lake
check(basin.sum() * h * h > 100, f"the closed basin lies below the level ({basin.sum() * h * h:.0f} m^2) apart "
      "from the lake")
check(abs(placed / lake_volume - 1) < 0.02, f"water placed {placed:.0f} m^3 vs the integral of level - terrain over "
      f"the lake {lake_volume:.0f} m^3 ({100 * (placed / lake_volume - 1):+.2f} %, within 2 %)")
thick = np.maximum(surface(z, x0, y0, d, X, Y) - surface(zb, x0, y0, d, X, Y), 0)
slide_integral = float(thick.sum() * h * h)
check(abs(slide_volume / slide_integral - 1) < 0.01, f"slide volume {slide_volume:.0f} m^3 vs the grids' integral "
      f"{slide_integral:.0f} m^3 (within 1 %)")
check(abs(cells / slide_volume - 1) < 0.02, f"{n_spheres} spheres of D = {D} m: their lattice cells hold "
      f"{cells:.0f} m^3 of the {slide_volume:.0f} m^3 ({100 * (cells / slide_volume - 1):+.2f} %, within 2 %)")

# --- the slide bonded: columns on the lattice's levels, so that neighbours in adjacent
# columns touch and bond too (stacked on the slope, only the spheres of one column touch:
# fewer bonds than spheres); the same spheres and mass
bonded = os.path.join(site, "bonded.yaml")
with open(bonded, "w") as f:
    f.write(open(case).read().replace("phi: 30, restitution: 0.3}", "phi: 30, restitution: 0.3, bond: {cn: 1e5, cs: 1e5}}"))
r = surge("check", bonded)
mb = re.search(r"spheres\s+(\d+), (\d+) bonds", r.stdout)
check(r.returncode == 0 and mb is not None and int(mb.group(1)) == n_spheres and int(mb.group(2)) > 1.5 * n_spheres,
      f"bonded slide: {mb.group(2) if mb else '?'} bonds among {mb.group(1) if mb else '?'} spheres (more than 1.5 "
      f"per sphere) " + r.stderr[-200:])

# --- a run to 1 s, restarted to 2 s, against a straight run to 2 s; then on to 9 s
out, straight = os.path.join(WORK, "run"), os.path.join(WORK, "straight")
r = surge("run", case, "--out", out, "--quiet", "--threads", "2", "--set", "time.end=1")
check(r.returncode == 0, "the run to 1 s completes " + r.stderr[-300:])


def band(name):
    ds = gdal.Open(os.path.join(out, "maps", name + ".tif"))
    a = ds.GetRasterBand(1).ReadAsArray().astype(float)
    a[a == ds.GetRasterBand(1).GetNoDataValue()] = np.nan
    gt = ds.GetGeoTransform()
    x = gt[0] + (np.arange(a.shape[1]) + 0.5) * gt[1]
    y = gt[3] + (np.arange(a.shape[0]) + 0.5) * gt[5]
    return a, np.meshgrid(x, y)


eta, (mx, my) = band("max_elevation")
wet = np.isfinite(eta)
check(wet.sum() > 300, f"{wet.sum()} map cells wet at 1 s")
far = wet & (mx < 600180)
check(far.sum() > 50 and np.nanmax(np.abs(eta[far] - level)) <= dp / 8,
      f"before the wave: the highest surface far from the slide (x < 180 m, {far.sum()} cells) is the still level "
      f"within dp/8 (largest difference {np.nanmax(np.abs(eta[far] - level)):.3f} m)")
check(np.nanmin(eta[wet]) >= level - dp / 8, f"the highest surface is at least the still level wherever it is wet "
      f"(lowest {np.nanmin(eta[wet]):.3f} m)")
basin_cells = (np.hypot(mx - 600080, my - 5100195) < 8)
check(not np.any(wet & basin_cells), "the closed basin stays dry in the maps")

with open(os.path.join(out, "maps", "runup.csv")) as f:
    base = {row["line"]: row for row in csv.DictReader(f)}
south0 = float(base["south_shore"]["run_up_z"])
check(abs(south0 - level) <= dp / 8, f"at rest the run-up reading on the south shore is the still level within dp/8 "
      f"({south0:.3f} m)")

r = surge("restart", out, "--quiet", "--threads", "2", "--set", "time.end=2")
check(r.returncode == 0, "the restart to 2 s completes " + r.stderr[-300:])
r = surge("run", case, "--out", straight, "--quiet", "--threads", "2", "--set", "time.end=2")
check(r.returncode == 0, "the straight run to 2 s completes " + r.stderr[-300:])
names = ["max_elevation.tif", "max_depth.tif", "max_speed.tif", "arrival_time.tif", "hazard.vti", "runup.csv"]
differ = [n for n in names if not filecmp.cmp(os.path.join(out, "maps", n), os.path.join(straight, "maps", n),
                                               shallow=False)]
check(not differ, f"restarted at 1 s, the maps at 2 s are those of the straight run, bit for bit "
      f"({', '.join(differ) or 'none differ'})")

r = surge("restart", out, "--quiet", "--threads", "2", "--set", "time.end=9")
check(r.returncode == 0, "the restart to 9 s completes " + r.stderr[-300:])
eta, (mx, my) = band("max_elevation")
near = np.isfinite(eta) & (np.abs(mx - 600250) < 30)
check(np.nanmax(eta[near]) > level + 0.5, f"the wave: the water near the slide rose {np.nanmax(eta[near]) - level:.2f} m"
      " above the still level (> 0.5 m)")
arrival, _ = band("arrival_time")
check(np.isfinite(arrival).sum() > 50, f"{np.isfinite(arrival).sum()} cells saw the wave arrive")
with open(os.path.join(out, "maps", "runup.csv")) as f:
    rows = {row["line"]: row for row in csv.DictReader(f)}
south = rows.get("south_shore", {})
check(bool(south.get("run_up_z")) and float(south["above_still_level"]) > 0 and
      float(south["run_up_z"]) >= south0 + 0.15,
      f"run-up on the far (south) shore above the still level: {south.get('above_still_level')} m, and at least "
      f"0.15 m above its reading at rest ({south0:.3f} m; wetted ground {south.get('ground_z')} m)")

# --- bad input: exit 2, the file named, nothing written
bad = os.path.join(WORK, "bad")
os.makedirs(bad)
for f in ("pre_failure.tif", "sliding_surface.tif"):
    shutil.copy(os.path.join(site, f), bad)
text = open(case).read()


def bad_case(name, old, new, expect):
    path = os.path.join(bad, name + ".yaml")
    with open(path, "w") as f:
        f.write(text.replace(old, new) if old else text)
    o = os.path.join(bad, "out_" + name)
    r = surge("run", path, "--out", o, "--quiet")
    check(r.returncode == 2 and expect in r.stderr and not os.path.exists(o),
          f"{name}: exit {r.returncode}, message names '{expect}', nothing written: {r.stderr.strip()[:160]}")


bad_case("seed_on_dry_land", "seed: [600300, 5100075]", "seed: [600080, 5100060]", "is on dry land")
bad_case("level_above_domain", "level: 1022", "level: 1060", "above the domain's top")
with open(os.path.join(bad, "not_a_grid.tif"), "w") as f:
    f.write("this is not a raster\n")
bad_case("not_a_raster", "terrain: sliding_surface.tif\ndem", "terrain: not_a_grid.tif\ndem",
         "not_a_grid.tif: not a raster")
# The sliding surface lifted 10 m above the pre-failure one over a corner of the site.
zc = gdal.Open(os.path.join(site, "sliding_surface.tif"))
drv = gdal.GetDriverByName("GTiff")
crossed = drv.CreateCopy(os.path.join(bad, "crossed.tif"), zc)
a = crossed.GetRasterBand(1).ReadAsArray()
a[:5, :5] += 10
crossed.GetRasterBand(1).WriteArray(a)
crossed = None
bad_case("crossed_surfaces", "bottom: sliding_surface.tif}", "bottom: crossed.tif}",
         "crossed.tif: the sliding surface lies above the pre-failure surface at 25 nodes (400.0 m^2)")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all reservoir checks passed")
