"""End-to-end tests of the surge program: bad input is rejected cleanly, a run
writes readable VTK (checked with VTK's own reader), gauges, summary and case.yaml,
a diverging run stops with exit code 3 keeping its earlier outputs, and Ctrl-C stops
cleanly."""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import surge_post  # noqa: E402

SURGE, WORK = sys.argv[1], sys.argv[2]
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(args, **kw):
    return subprocess.run([SURGE] + args, capture_output=True, text=True, **kw)


GOOD = """name: tiny
dp: 0.02
time: {end: 0.06, output_every: 0.02, gauge_every: 0.01}
domain: {min: [0, 0, 0], max: [0.4, 0.1, 0.4]}
fluid:
  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}
walls:
  - {name: tank, box: {min: [0, 0, 0], max: [0.4, 0.1, 0.3]}, open: [zmax]}
gauges:
  - {name: H1, type: height, x: 0.05, y: 0.05}
  - {name: P1, type: pressure, at: [0.05, 0.05, 0.03]}
"""

shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)


def write(name, text):
    p = os.path.join(WORK, name)
    with open(p, "w") as f:
        f.write(text)
    return p


# --- command line basics
r = run(["--version"])
check(r.returncode == 0 and "surge" in r.stdout, "--version")
r = run(["--help"])
check(r.returncode == 0 and "surge run CASE" in r.stdout, "--help")
r = run(["frobnicate"])
check(r.returncode == 2, "unknown command exits 2")

# --- bad input: one message naming file, line and key; exit 2; nothing written
bad_cases = {
    "malformed": (GOOD.replace("dp: 0.02", "dp: [0.02"), "malformed YAML"),
    "typo": (GOOD.replace("time: {end", "time: {ned"), "'time.ned'"),
    "wrong_type": (GOOD.replace("dp: 0.02", "dp: small"), "'dp': expected a number"),
    "missing_mesh": (GOOD.replace("walls:\n", "walls:\n  - {mesh: nowhere.stl}\n"), "'walls.0.mesh'"),
    "negative_dp": (GOOD.replace("dp: 0.02", "dp: -0.02"), "'dp': particle spacing must be positive"),
    "outside": (GOOD.replace("max: [0.1, 0.1, 0.2]", "max: [0.1, 0.1, 0.5]"), "outside the domain"),
    "empty_region": (GOOD.replace("max: [0.1, 0.1, 0.2]", "max: [0.1, 0.01, 0.2]"), "thinner than dp"),
    "unknown_shifting": (GOOD.replace("fluid:", "sph: {shifting: lind}\nfluid:"), "'sph.shifting'"),
    "unknown_viscosity": (GOOD.replace("fluid:", "sph: {viscosity: sps}\nfluid:"), "'sph.viscosity'"),
    "negative_shifting": (GOOD.replace("fluid:", "sph: {shifting: fickian, shifting_coefficient: -2}\nfluid:"),
                          "'sph.shifting_coefficient'"),
    "negative_nu": (GOOD.replace("fluid:", "sph: {viscosity: laminar, nu: -1.0e-6}\nfluid:"), "'sph.nu'"),
    "particles_and_box": (GOOD.replace("  - box: {min", "  - particles: water.csv\n    box: {min"),
                          "exactly one of 'box', 'reservoir' or 'particles'"),
    "fill_reservoir": (GOOD.replace("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}",
                                    "  - {reservoir: {level: 0.1, seed: [0.05, 0.05]}, fill: lattice}"),
                       "'fluid.0.fill'"),
    "missing_particles": (GOOD.replace("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}", "  - particles: none.csv"),
                          "'fluid.0.particles'"),
}
for name, (text, fragment) in bad_cases.items():
    path = write(f"bad_{name}.yaml", text)
    out = os.path.join(WORK, f"out_bad_{name}")
    for cmd in (["check", path], ["run", path, "--out", out]):
        r = run(cmd)
        lines = [l for l in r.stderr.strip().splitlines() if l]
        check(r.returncode == 2, f"{name}: {cmd[0]} exits 2 (got {r.returncode})")
        check(len(lines) >= 1 and lines[0].startswith("error: " + path), f"{name}: message names the file: {lines[:1]}")
        check(fragment in r.stderr, f"{name}: message says '{fragment}'")
        if name not in ("malformed",):
            check(":" in lines[0][len("error: " + path):][:8], f"{name}: message gives a line number")
    check(not os.path.exists(out), f"{name}: nothing written to the output folder")

# A particle table with a bad row: the table's file and line named, exit 2.
write("water_bad.csv", "x,y,z,vx,vy,vz\n0.01,0.01,0.01,0,0,0\n0.03,0.01,zero,0,0,0\n")
r = run(["check", write("bad_table.yaml", GOOD.replace("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}",
                                                        "  - particles: water_bad.csv"))])
check(r.returncode == 2 and "water_bad.csv:3" in r.stderr and "'zero' is not a finite number" in r.stderr,
      f"a bad particle table names its file and line ({r.stderr.strip()[:160]})")
write("water_out.csv", "0.01,0.01,0.01,0,0,0\n0.01,0.01,0.9,0,0,0,1000\n")
r = run(["check", write("out_table.yaml", GOOD.replace("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}",
                                                        "  - particles: water_out.csv"))])
check(r.returncode == 2 and "water_out.csv:2" in r.stderr and "outside the domain" in r.stderr,
      f"a table's particle outside the domain is named ({r.stderr.strip()[:160]})")

r = run(["check", write("good.yaml", GOOD), "--set", "time.ned=1"])
check(r.returncode == 2 and "--set" in r.stderr, "--set typo is rejected and attributed to --set")

# --- surge check on a good case
r = run(["check", os.path.join(WORK, "good.yaml")])
check(r.returncode == 0 and "fluid" in r.stdout and "first dt" in r.stdout and "run time" in r.stdout, "check prints counts, dt, run time")
check("0.002 m^3 placed of 0.002 m^3" in r.stdout and "100.0 %" in r.stdout, "check reports the water placed (whole spacings)")
check("delta_plus" not in r.stdout, "no shifting warning with the default fickian shifting")
r = run(["check", os.path.join(WORK, "good.yaml"), "--set", "sph.shifting=delta_plus"])
check(r.returncode == 0 and "delta_plus under gravity: at a free surface it lifts the water" in r.stdout,
      "check warns that delta_plus shifting lifts a free surface")
# A box 0.11 m wide at dp = 0.02 holds its own volume (6 layers of 0.0183 m, the mass from it) ...
r = run(["check", os.path.join(WORK, "good.yaml"), "--set", "fluid.0.box.max=[0.11,0.1,0.2]"])
check(r.returncode == 0 and "0.0022 m^3 placed of 0.0022 m^3" in r.stdout and "100.0 %" in r.stdout
      and "not whole numbers of dp" not in r.stdout, "check reports the exact fill of a box of 5.5 dp")
# ... and with fill: lattice 5 layers (0.1 m): 90.9 % of the water, said and warned.
r = run(["check", os.path.join(WORK, "good.yaml"), "--set", "fluid.0.box.max=[0.11,0.1,0.2]", "--set",
         "fluid.0.fill=lattice"])
check(r.returncode == 0 and "0.002 m^3 placed of 0.0022 m^3" in r.stdout and "90.9 %" in r.stdout
      and "not whole numbers of dp" in r.stdout, "check reports and warns about water short of its box (fill: lattice)")

# --- a good run
out = os.path.join(WORK, "out_good")
r = run(["run", os.path.join(WORK, "good.yaml"), "--out", out, "--threads", "2"])
check(r.returncode == 0, f"good run exits 0 ({r.stderr[-300:]})")
for f in ["fluid.pvd", "walls.pvd", "gauges.csv", "summary.json", "case.yaml"]:
    check(os.path.isfile(os.path.join(out, f)), f"writes {f}")
check(not any(n.endswith(".tmp") for _, _, fs in os.walk(out) for n in fs), "no temporary files left")
summary = surge_post.read_summary(os.path.join(out, "summary.json"))
check(summary["status"] == "completed" and summary["exit_code"] == 0, "summary status")
frames = surge_post.read_pvd(os.path.join(out, "fluid.pvd"))
check([round(t, 6) for t, _ in frames] == [0.0, 0.02, 0.04, 0.06], f"one frame per output time: {[t for t, _ in frames]}")
first = surge_post.read_vtp(frames[0][1])
n = summary["particles"]["fluid"]
check(len(first["id"]) == n == 5 * 5 * 10, f"first frame holds every fluid particle ({len(first['id'])} vs {n})")
# Values: the fluid starts on the (i + 1/2) dp lattice in hydrostatic balance (Tait).
pos = first["position"]
lattice = np.abs((pos / 0.02 - 0.5) - np.round(pos / 0.02 - 0.5)).max()
check(lattice < 1e-6, f"positions on the lattice (max deviation {lattice:.2e} dp)")
c0 = 20 * np.sqrt(9.81 * 0.2)
B = c0 ** 2 * 1000 / 7
rho_expected = 1000 * (1 + 1000 * 9.81 * (0.2 - pos[:, 2]) / B) ** (1 / 7)
check(np.abs(first["density"] - rho_expected).max() < 0.01, "initial density is hydrostatic (Tait)")
check(np.abs(first["pressure"] - B * ((first["density"] / 1000) ** 7 - 1)).max() < 1.0, "pressure = Tait(density)")
check(len(np.unique(first["id"])) == n and (first["kind"] == 0).all(), "ids unique, kind fluid")
check(np.abs(first["velocity"]).max() == 0.0, "fluid starts at rest")
last = surge_post.read_vtp(frames[-1][1])
check(last["position"][:, 2].min() > 0 and last["position"][:, 0].max() < 0.4, "last frame inside the tank")
check(np.abs(last["velocity"]).max() > 0.1, "the column is collapsing")
walls = surge_post.read_vtp(surge_post.read_pvd(os.path.join(out, "walls.pvd"))[0][1])
check(len(walls["id"]) == summary["particles"]["wall"] and (walls["kind"] == 1).all(), "walls file")
names, g = surge_post.read_gauges(os.path.join(out, "gauges.csv"))
check(names == ["time", "H1", "P1"], f"gauge columns {names}")
check(len(g) == 7 and abs(g[0, 1] - 0.2) < 0.02, f"gauge rows and initial height ({g[0, 1] if len(g) else None})")
check(abs(g[0, 2] - 1000 * 9.81 * 0.17) < 0.1 * 1000 * 9.81 * 0.17, f"initial pressure near rho g (H - z) ({g[0, 2]})")
r = run(["check", os.path.join(out, "case.yaml")])
check(r.returncode == 0, "case.yaml as written is a valid case")
# ... and with a particle table (fill is a box's: case.yaml must not give it to the table)
write("water_ok.csv", "x,y,z,vx,vy,vz\n0.01,0.05,0.01,0,0,0\n0.03,0.05,0.01,0,0,0\n0.01,0.05,0.03,0,0,0\n")
out_t = os.path.join(WORK, "out_table")
r = run(["run", write("table.yaml", GOOD.replace("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}",
                                                  "  - particles: water_ok.csv")), "--out", out_t, "--quiet",
         "--set", "time.end=0.02"])
r2 = run(["check", os.path.join(out_t, "case.yaml")])
check(r.returncode == 0 and r2.returncode == 0, f"a particle table's run writes a valid case.yaml ({r2.stderr[-200:]})")

# --- restart: a run stopped at 0.03 s and continued to 0.06 s ends bitwise identical
out_a, out_b = os.path.join(WORK, "out_straight"), os.path.join(WORK, "out_restarted")
run(["run", os.path.join(WORK, "good.yaml"), "--out", out_a, "--quiet"])
run(["run", os.path.join(WORK, "good.yaml"), "--out", out_b, "--quiet", "--set", "time.end=0.03"])
r = run(["restart", out_b, "--set", "time.end=0.06"])
check(r.returncode == 0 and "restarting at t = 0.03" in r.stderr, f"restart runs ({r.stderr[-200:]})")
fa, fb = surge_post.read_pvd(os.path.join(out_a, "fluid.pvd")), surge_post.read_pvd(os.path.join(out_b, "fluid.pvd"))
check(abs(fa[-1][0] - 0.06) < 1e-9 and abs(fb[-1][0] - 0.06) < 1e-9, "both end at 0.06 s")
with open(fa[-1][1], "rb") as x, open(fb[-1][1], "rb") as y:
    check(x.read() == y.read(), "restarted run's last frame is bitwise identical to the straight run's")
with open(os.path.join(out_a, "gauges.csv")) as x, open(os.path.join(out_b, "gauges.csv")) as y:
    check(x.read() == y.read(), "gauges.csv identical after restart")
# ... and with laminar_sps, whose stress each particle carries from step to step (in the
# checkpoint: version 5)
sa, sb = os.path.join(WORK, "sps_straight"), os.path.join(WORK, "sps_restarted")
sps = ["--set", "sph.viscosity=laminar_sps", "--set", "time.end=0.06"]
run(["run", os.path.join(WORK, "good.yaml"), "--out", sa, "--quiet"] + sps)
run(["run", os.path.join(WORK, "good.yaml"), "--out", sb, "--quiet"] + sps + ["--set", "time.end=0.03"])
with open(os.path.join(sb, "checkpoint.bin"), "rb") as x:
    check(x.read(8)[7:] == b"5", "a laminar_sps checkpoint is version 5 (it holds the stress)")
r = run(["restart", sb, "--set", "time.end=0.06"])
fa, fb = surge_post.read_pvd(os.path.join(sa, "fluid.pvd")), surge_post.read_pvd(os.path.join(sb, "fluid.pvd"))
with open(fa[-1][1], "rb") as x, open(fb[-1][1], "rb") as y:
    check(r.returncode == 0 and x.read() == y.read(), "laminar_sps: the restarted run's last frame is bitwise identical")
# A restart asking for denser frames gets them from where it starts, not from the old
# schedule's next frame on.
r = run(["restart", out_b, "--set", "time.end=0.07", "--set", "time.output_every=0.002"])
late = [t for t, _ in surge_post.read_pvd(os.path.join(out_b, "fluid.pvd")) if t > 0.06 + 1e-9]
check(r.returncode == 0 and len(late) == 5 and abs(late[0] - 0.062) < 1e-9,
      f"a restart with output_every 0.002 writes frames at 0.062 ... 0.07 ({late})")
r = run(["restart", os.path.join(WORK, "out_bad_typo")])
check(r.returncode == 2, "restart of a folder without a run exits 2")
# --- issue 34's bad input: --out naming a file, a folder as the case, a Courant number above 1
good = write("good_for_out.yaml", GOOD)
not_a_folder = write("not_a_folder.txt", "keep me\n")
r = run(["run", good, "--out", not_a_folder, "--quiet"])
check(r.returncode == 2 and "--out" in r.stderr and "not a folder" in r.stderr and
      open(not_a_folder).read() == "keep me\n", f"--out naming a file exits 2 and leaves it ({r.stderr.strip()})")
r = run(["check", WORK])
check(r.returncode == 2 and "is a folder" in r.stderr, f"a folder as the case file exits 2 ({r.stderr.strip()})")
r = run(["check", good, "--set", "sph.cfl=5"])
check(r.returncode == 0 and "sph.cfl = 5 is above 1" in r.stdout, f"surge check warns of sph.cfl = 5 ({r.stdout[-200:]})")

# --- a killed run loses at most time.checkpoint_every_wall of work: the run below writes
# a checkpoint every 0.2 s of wall time between its outputs (0.05 s apart in simulated
# time); it is killed with SIGKILL (no chance to save anything) after at least two such
# checkpoints, restarted, and must end bitwise identical to an uninterrupted run.
KILL = GOOD.replace("dp: 0.02", "dp: 0.01").replace(
    "time: {end: 0.06, output_every: 0.02, gauge_every: 0.01}",
    "time: {end: 0.1, output_every: 0.05, gauge_every: 0.01, checkpoint_every_wall: 0.2}")
kill_case = write("kill.yaml", KILL)
ka, kb = os.path.join(WORK, "kill_straight"), os.path.join(WORK, "kill_restarted")
run(["run", kill_case, "--out", ka, "--quiet", "--threads", "1"])
proc = subprocess.Popen([SURGE, "run", kill_case, "--out", kb, "--quiet", "--threads", "1"],
                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
ck, stamps = os.path.join(kb, "checkpoint.bin"), set()
deadline = time.time() + 120
while proc.poll() is None and time.time() < deadline and len(stamps) < 4:
    if os.path.exists(ck):
        stamps.add(os.stat(ck).st_mtime_ns)
    time.sleep(0.02)
proc.send_signal(signal.SIGKILL)
proc.wait()
r = run(["restart", kb, "--threads", "1"])
t_restart = float(r.stderr.split("restarting at t = ")[1].split()[0]) if "restarting at t = " in r.stderr else -1
between = t_restart > 0 and abs(t_restart / 0.05 - round(t_restart / 0.05)) > 1e-6
check(r.returncode == 0 and between, f"killed run restarts from a checkpoint between outputs (t = {t_restart})")
for name in ["particles/fluid_0002.vtp", "gauges.csv"]:
    pa, pb = os.path.join(ka, name), os.path.join(kb, name)
    same = os.path.exists(pa) and os.path.exists(pb) and open(pa, "rb").read() == open(pb, "rb").read()
    check(same, f"killed and restarted run: {name} bitwise identical to the uninterrupted run")

# --- a DEM-only run from its case file: the paper's slide body on the slope
case_dir = os.path.join(os.path.dirname(__file__), "..", "..", "cases")
out_dem = os.path.join(WORK, "out_slide")
r = run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", out_dem, "--set", "time.end=0.3", "--quiet"])
check(r.returncode == 0, f"DEM slide runs ({r.stderr[-200:]})")
sf = surge_post.read_pvd(os.path.join(out_dem, "spheres.pvd"))
s0, s1 = surge_post.read_vtp(sf[0][1]), surge_post.read_vtp(sf[-1][1])
check(len(s0["id"]) == 522 and np.allclose(s0["radius"], 0.03), "522 spheres of r = 0.03 m in the VTK file")
check(abs(np.linalg.norm(s0["velocity"], axis=1).mean() - 1.0) < 1e-5, "initial speed 1 m/s")
check(s1["position"][:, 0].mean() > s0["position"][:, 0].mean() + 0.2, "the slide moved down the slope")
check(s1["contacts"].max() >= 1 and "angular_velocity" in s1, "contact counts and angular velocity written")
check(surge_post.read_summary(os.path.join(out_dem, "summary.json"))["particles"]["sphere"] == 522, "summary counts spheres")
# DEM wall gauges: the slide (weight W = 522 m g) rests on the slope. Its spheres bounce,
# so the load is read as a time mean over 0.05-0.3 s, where the vertical force on the
# slope is W minus the slide's vertical acceleration: between the value for a block
# sliding with the wall's friction (10 deg: a = g (sin 27.1 - tan 10 cos 27.1), load
# 0.863 W) and W (no acceleration); the floor carries nothing while the slide is on the
# slope.
names, gd = surge_post.read_gauges(os.path.join(out_dem, "gauges.csv"))
W = 522 * 2500 * 4 / 3 * np.pi * 0.03**3 * 9.81
late = gd[:, 0] > 0.05
fz = gd[late, names.index("slope_fz")].mean()
check(names[:4] == ["time", "slope_fx", "slope_fz", "floor_fz"] and len(gd) > 10, f"DEM gauges written ({names})")
check(-1.0 * W < fz < -0.8 * W, f"slope carries the slide (mean F_z = {fz:.0f} N = {-fz / W:.3f} W)")
check(np.all(gd[:, names.index("floor_fz")] == 0), "floor unloaded while the slide is on the slope")
# The same with Hertz-Mindlin (dem.contact): the same bounds on the slope's load hold for
# any contact law with the walls' friction, and its restart is bitwise too.
out_hm = os.path.join(WORK, "dem_slide_hertz")
r = run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", out_hm, "--set", "time.end=0.3", "--quiet",
         "--set", "dem.contact=hertz_mindlin"])
check(r.returncode == 0, f"DEM slide runs with Hertz-Mindlin ({r.stderr[-200:]})")
names_hm, gd_hm = surge_post.read_gauges(os.path.join(out_hm, "gauges.csv"))
fz_hm = gd_hm[gd_hm[:, 0] > 0.05, names_hm.index("slope_fz")].mean()
check(-1.0 * W < fz_hm < -0.8 * W, f"Hertz-Mindlin: slope carries the slide (mean F_z = {-fz_hm / W:.3f} W)")
ha, hb = os.path.join(WORK, "dem_hertz_straight"), os.path.join(WORK, "dem_hertz_restarted")
hset = ["--set", "time.output_every=0.05", "--set", "dem.contact=hertz_mindlin", "--quiet"]
run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", ha, "--set", "time.end=0.1"] + hset)
run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", hb, "--set", "time.end=0.05"] + hset)
r = run(["restart", hb, "--set", "time.end=0.1"])
same = all(open(os.path.join(ha, n), "rb").read() == open(os.path.join(hb, n), "rb").read()
           for n in ["particles/spheres_0002.vtp", "gauges.csv"])
check(r.returncode == 0 and same, "Hertz-Mindlin DEM restart bitwise identical")
# DEM-only restart: stopped at 0.05 s and continued to 0.1 s, bitwise identical.
da, db = os.path.join(WORK, "dem_straight"), os.path.join(WORK, "dem_restarted")
dset = ["--set", "time.output_every=0.05", "--quiet"]
run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", da, "--set", "time.end=0.1"] + dset)
run(["run", os.path.join(case_dir, "slide_dem_only.yaml"), "--out", db, "--set", "time.end=0.05"] + dset)
r = run(["restart", db, "--set", "time.end=0.1"])
check(r.returncode == 0 and "restarting at t = 0.05" in r.stderr, f"DEM restart runs ({r.stderr[-200:]})")
for name in ["particles/spheres_0002.vtp", "gauges.csv"]:
    pa, pb = os.path.join(da, name), os.path.join(db, name)
    same = os.path.exists(pa) and os.path.exists(pb) and open(pa, "rb").read() == open(pb, "rb").read()
    check(same, f"DEM restart: {name} bitwise identical")
bad_dem = write("bad_dem.yaml", open(os.path.join(case_dir, "slide_dem_only.yaml")).read()
                .replace("mesh: slide_slope.stl", "mesh: " + os.path.abspath(os.path.join(case_dir, "slide_slope.stl")))
                .replace("csv: slide_spheres.csv, material: rock",
                         "csv: " + os.path.abspath(os.path.join(case_dir, "slide_spheres.csv")) + ", material: granite"))
r = run(["check", bad_dem])
check(r.returncode == 2 and "no DEM material named 'granite'" in r.stderr, f"unknown DEM material is rejected ({r.stderr.strip()[:120]})")

# --- a random loose pack settled under gravity before the run: 200 spheres dropped into a
# box; after 0.6 s of settling they rest on the floor: every sphere inside the walls (up
# to 2 % of r of overlap), the pack lower than where it started, nearly at rest.
SETTLE = """name: settled
time: {end: 0.01, output_every: 0.01}
domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.3]}
dem:
  materials: [{name: sand, restitution: 0.3}]
  walls:
    - {plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: sand}
    - {plane: {point: [0, 0, 0], normal: [1, 0, 0]}, material: sand}
    - {plane: {point: [0.1, 0, 0], normal: [-1, 0, 0]}, material: sand}
    - {plane: {point: [0, 0, 0], normal: [0, 1, 0]}, material: sand}
    - {plane: {point: [0, 0.1, 0], normal: [0, -1, 0]}, material: sand}
  packs: [{box: {min: [0, 0, 0.1], max: [0.1, 0.1, 0.3]}, radius: 0.006, random: 200, settle: 0.6, material: sand}]
"""
out_s = os.path.join(WORK, "out_settled")
r = run(["run", write("settled.yaml", SETTLE), "--out", out_s, "--quiet"])
check(r.returncode == 0, f"random pack settles and runs ({r.stderr[-200:]})")
if r.returncode == 0:
    s0 = surge_post.read_vtp(surge_post.read_pvd(os.path.join(out_s, "spheres.pvd"))[0][1])
    p = s0["position"]
    check(len(p) == 200, "200 spheres")
    check(p[:, 2].min() > 0.006 * 0.98 and p[:, :2].min() > 0.006 * 0.98 and p[:, :2].max() < 0.1 - 0.006 * 0.98,
          "settled spheres inside the walls")
    check(p[:, 2].max() < 0.1, f"the pack fell to the floor (top centre at {p[:, 2].max():.3f} m)")
    check(np.linalg.norm(s0["velocity"], axis=1).max() == 0, "the run starts from rest")

# --- a bonded DEM block: bonds written as VTK lines, counted in the summary
BONDED = """name: bonded
time: {end: 0.02, output_every: 0.01}
domain: {min: [0, 0, 0], max: [0.2, 0.2, 0.2]}
dem:
  materials: [{name: rock, bond: {cn: 1.0e6, cs: 1.0e6}}]
  walls: [{plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: rock}]
  packs: [{box: {min: [0, 0, 0], max: [0.08, 0.08, 0.08]}, radius: 0.01, material: rock}]
"""
out_b = os.path.join(WORK, "out_bonded")
r = run(["run", write("bonded.yaml", BONDED), "--out", out_b, "--quiet"])
sb = surge_post.read_summary(os.path.join(out_b, "summary.json"))
check(r.returncode == 0 and sb["dem"]["bonds"] == 3 * 4 * 4 * 3, f"4x4x4 lattice pack has 144 bonds ({sb['dem']})")
bf = surge_post.read_pvd(os.path.join(out_b, "spheres.pvd"))
lines = surge_post.read_vtp_lines(bf[-1][1])
pts = surge_post.read_vtp(bf[-1][1])["position"]
lengths = np.linalg.norm(pts[lines[:, 0]] - pts[lines[:, 1]], axis=1) if len(lines) else np.zeros(0)
check(len(lines) == 144 and np.abs(lengths - 0.02).max() < 1e-3, f"bonds written as 144 lines of length 2r ({len(lines)})")

# --- a diverging run: CFL far above its limit
out_bad = os.path.join(WORK, "out_unstable")
r = run(["run", os.path.join(WORK, "good.yaml"), "--out", out_bad, "--set", "sph.cfl=8", "--set", "time.end=0.5",
         "--set", "time.output_every=0.005"], timeout=300)
check(r.returncode == 3, f"unstable run exits 3 (got {r.returncode}; {r.stderr[-300:]})")
check("diverged" in r.stderr, "message says it diverged")
s = surge_post.read_summary(os.path.join(out_bad, "summary.json"))
check(s["status"] == "diverged" and s["exit_code"] == 3, "summary records the divergence")
good_frames = surge_post.read_pvd(os.path.join(out_bad, "fluid.pvd"))
ok = True
for t, f in good_frames:
    d = surge_post.read_vtp(f)
    ok = ok and np.isfinite(d["position"]).all() and np.isfinite(d["density"]).all() and len(d["id"]) > 0
check(ok and len(good_frames) >= 1, f"the {len(good_frames)} earlier outputs are intact and finite")

# --- Ctrl-C stops cleanly after writing what it has
out_int = os.path.join(WORK, "out_interrupted")
p = subprocess.Popen([SURGE, "run", os.path.join(WORK, "good.yaml"), "--out", out_int, "--set", "time.end=100", "--set", "dp=0.01"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
deadline = time.time() + 60
while time.time() < deadline and not os.path.exists(os.path.join(out_int, "summary.json")):
    time.sleep(0.2)
time.sleep(1.0)
p.send_signal(signal.SIGINT)
_, err = p.communicate(timeout=120)
check(p.returncode == 130, f"interrupted run exits 130 (got {p.returncode})")
s = surge_post.read_summary(os.path.join(out_int, "summary.json"))
check(s["status"] == "interrupted", "summary says interrupted")
fr = surge_post.read_pvd(os.path.join(out_int, "fluid.pvd"))
check(len(fr) >= 2 and len(surge_post.read_vtp(fr[-1][1])["id"]) > 0, "final state written on interrupt")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
