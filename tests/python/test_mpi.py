"""Distributed runs (MPI build): the same case on 1, 2 and 3 processes gives the same
bits -- gauges, every particle file, the checkpoint -- on a dam break, on the coupled
slide at coarse resolution, on the reservoir from elevation grids (hazard maps included),
on Archimedes with mDBC and the symplectic integrator, on
the DEM-only column, on a floating box and on a block thrown onto gravel (walls that move),
on a periodic flume with a damping zone, on a dam break with a symmetry plane (images;
and with laminar_sps, whose stress the particles carry, restarted on another count), on
slabs along a periodic axis (a box periodic along every axis, a flume periodic along its
length) and on spheres sinking on a periodic face and against their mirror image;
a checkpoint written by 3 processes continues on 2 exactly as the straight run; bad
input, divergence and Ctrl-C end every process with the single-process exit codes.

usage: test_mpi.py SURGE WORK CASES"""
import filecmp
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import sinking_case  # noqa: E402

SURGE, WORK, CASES = sys.argv[1], sys.argv[2], sys.argv[3]
MPIRUN = shutil.which("mpirun")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mpi(n, args, timeout=600):
    # One thread per process: 3 processes on this 2-core machine already oversubscribe it.
    cmd = [MPIRUN, "--oversubscribe", "-n", str(n)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE")
    return subprocess.run(cmd + [SURGE] + args + ["--threads", "1"], capture_output=True, text=True,
                          timeout=timeout, env=env)


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def same_files(a, b, what):
    """Every gauge, particle, checkpoint and hazard-map file of run a equals run b, byte for byte."""
    names = ["gauges.csv", "checkpoint.bin"] + sorted(
        os.path.relpath(f, a) for f in glob.glob(os.path.join(a, "particles", "*.vtp")) +
        glob.glob(os.path.join(a, "maps", "*")))
    diff = [n for n in names if not os.path.exists(os.path.join(b, n))
            or not filecmp.cmp(os.path.join(a, n), os.path.join(b, n), shallow=False)]
    check(not diff, f"{what}: {len(names)} files bitwise equal ({', '.join(diff[:4]) or 'none differ'})")


def runs_on(ranks, name, case, sets):
    outs = {}
    for n in ranks:
        out = os.path.join(WORK, f"{name}_{n}")
        t0 = time.time()
        r = mpi(n, ["run", case, "--out", out, "--quiet"] + sets)
        check(r.returncode == 0, f"{name} on {n} process(es) runs ({time.time() - t0:.0f} s; exit {r.returncode}"
              f"{': ' + r.stderr[-300:] if r.returncode else ''})")
        outs[n] = out
    return outs


if MPIRUN is None:
    print("FAIL mpirun not found (Debian: openmpi-bin)")
    sys.exit(1)
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# --- dam break: at least 300 steps, the front collapsing across slab faces
dam = runs_on([1, 2, 3], "dambreak", os.path.join(CASES, "demo_dambreak.yaml"),
              ["--set", "time.end=0.03", "--set", "time.output_every=0.015"])
s1, s3 = summary(dam[1]), summary(dam[3])
check(s1["steps"] >= 300, f"dam break: {s1['steps']} steps (>= 300)")
check(s1["distributed"]["ranks"] == 1 and s3["distributed"]["ranks"] == 3, "summary.json gives the process count")
check(s3["distributed"]["rank0"]["bytes_sent_per_exchange"] > 0 and s3["distributed"]["rank0"]["halo_particles"] > 0,
      "3 processes exchange halos (%.0f B per exchange from rank 0)" % s3["distributed"]["rank0"]["bytes_sent_per_exchange"])
check(s3["particles"]["now"] == s1["particles"]["now"], "the same particle count on 3 processes as on 1")
for n in (2, 3):
    same_files(dam[1], dam[n], f"dam break, 1 and {n} processes")

# --- wall-clock checkpoints between outputs (every 0.2 s of wall time): a gather every
# process must join, decided together although each has its own clock
out = os.path.join(WORK, "dambreak_wallck")
r = mpi(3, ["run", os.path.join(CASES, "demo_dambreak.yaml"), "--out", out, "--quiet", "--set", "time.end=0.03",
            "--set", "time.output_every=0.015", "--set", "time.checkpoint_every_wall=0.2"], timeout=300)
check(r.returncode == 0, f"3 processes with wall-clock checkpoints every 0.2 s finish (exit {r.returncode})")
same_files(dam[1], out, "dam break with wall-clock checkpoints on 3 processes, against 1 without")

# --- the reservoir from elevation grids: terrain, lake, slide between grids, hazard maps
res = runs_on([1, 2, 3], "reservoir", os.path.join(CASES, "reservoir", "reservoir.yaml"),
              ["--set", "time.end=0.4", "--set", "time.output_every=0.2", "--set", "time.gauge_every=0.05"])
check(len(glob.glob(os.path.join(res[1], "maps", "*.tif"))) == 4, "reservoir: four hazard maps written")
for n in (2, 3):
    same_files(res[1], res[n], f"reservoir with hazard maps, 1 and {n} processes")

# --- the coupled slide at dp = 0.04 m: spheres entering the water, DEM on every process
slide_sets = ["--set", "dp=0.04", "--set", "time.end=0.075", "--set", "time.output_every=0.025"]
slide = runs_on([1, 2, 3], "slide", os.path.join(CASES, "slide_tsunami.yaml"), slide_sets)
check(summary(slide[1])["steps"] >= 300, f"slide: {summary(slide[1])['steps']} steps (>= 300)")
for n in (2, 3):
    same_files(slide[1], slide[n], f"coupled slide, 1 and {n} processes")

# --- restart on another process count: written by 3 processes, continued by 2
out = os.path.join(WORK, "slide_restart")
r = mpi(3, ["run", os.path.join(CASES, "slide_tsunami.yaml"), "--out", out, "--quiet", "--set", "dp=0.04",
            "--set", "time.end=0.05", "--set", "time.output_every=0.025"])
check(r.returncode == 0, f"slide to t = 0.05 s on 3 processes (exit {r.returncode})")
r = mpi(2, ["restart", out, "--quiet", "--set", "time.end=0.075"])
check(r.returncode == 0, f"restart on 2 processes (exit {r.returncode}: {r.stderr[-300:]})")
same_files(slide[1], out, "slide written by 3 processes, continued by 2, against 1 straight")

# --- mDBC ghosts (sphere and walls) and the two-evaluation symplectic step: the widest halo
arch = runs_on([1, 3], "archimedes", os.path.join(CASES, "archimedes.yaml"),
               ["--set", "time.end=0.02", "--set", "time.output_every=0.01", "--set", "sph.boundary=mdbc",
                "--set", "sph.integrator=symplectic"])
same_files(arch[1], arch[3], "Archimedes with mdbc and symplectic, 1 and 3 processes")

# --- a DEM-only case: every process advances the same spheres, rank 0 writes; a
# checkpoint written by 3 processes continues on 1 as the straight run
col_sets = ["--set", "time.end=0.05", "--set", "time.output_every=0.025"]
col = runs_on([1, 2, 3], "column", os.path.join(CASES, "column_collapse.yaml"), col_sets)
for n in (2, 3):
    same_files(col[1], col[n], f"DEM-only column, 1 and {n} processes")
check(summary(col[3])["distributed"]["ranks"] == 3, "DEM-only summary.json gives the process count")
out = os.path.join(WORK, "column_restart")
r = mpi(3, ["run", os.path.join(CASES, "column_collapse.yaml"), "--out", out, "--quiet", "--set", "time.end=0.025",
            "--set", "time.output_every=0.025"])
check(r.returncode == 0, f"DEM-only column to t = 0.025 s on 3 processes (exit {r.returncode})")
r = mpi(1, ["restart", out, "--quiet", "--set", "time.end=0.05"])
check(r.returncode == 0, f"DEM-only restart on 1 process (exit {r.returncode}: {r.stderr[-300:]})")
same_files(col[1], out, "DEM-only column written by 3 processes, continued by 1, against 1 straight")

# --- walls that move: a free floating box (its load summed over every process's wall
# particles in id order) and the DEM-only block on gravel (a free DEM body)
flo = runs_on([1, 3], "floating_box", os.path.join(CASES, "floating_box.yaml"),
              ["--set", "time.end=0.02", "--set", "time.output_every=0.01"])
same_files(flo[1], flo[3], "floating box (a free body), 1 and 3 processes")
bo = runs_on([1, 3], "boulder", os.path.join(CASES, "boulder_on_gravel.yaml"),
             ["--set", "time.end=0.08", "--set", "time.output_every=0.04"])
same_files(bo[1], bo[3], "block on gravel (a free DEM body), 1 and 3 processes")

# --- coupling.force_sum: per_sphere (per-process sphere sums added in rank order): equal to
# one process to round-off (relative 1e-5), not necessarily bitwise; the fixed sphere leaves
# the water's bits alone
ps = runs_on([1, 3], "archimedes_per_sphere", os.path.join(CASES, "archimedes.yaml"),
             ["--set", "time.end=0.02", "--set", "time.output_every=0.01", "--set", "coupling.force_sum=per_sphere"])


def gauge_rows(out):
    with open(os.path.join(out, "gauges.csv")) as f:
        next(f)
        return [[float(x) for x in line.split(",")] for line in f]


g1, g3 = gauge_rows(ps[1]), gauge_rows(ps[3])
scale = max(abs(r[1]) for r in g1)
worst = max(abs(a - b) for r1, r3 in zip(g1, g3) for a, b in zip(r1[1:], r3[1:])) / scale
check(len(g1) == len(g3) and worst <= 1e-5,
      f"per_sphere on 3 processes: sphere forces within 1e-5 of one process (worst {worst:.1e} of max |Fz|)")
s1 = summary(ps[3])
check(s1["distributed"]["ranks"] == 3, "per_sphere run on 3 processes")

# --- images (issue 33): a flume periodic across its width with a moving paddle and an
# absorbing zone (slabs along x, images along y on every process), and the demo dam break
# with a symmetry plane at its far end across the decomposed axis (x)
fl = runs_on([1, 2, 3], "absorbing_flume", os.path.join(CASES, "absorbing_flume.yaml"),
             ["--set", "time.end=0.04", "--set", "time.output_every=0.02"])
for n in (2, 3):
    same_files(fl[1], fl[n], f"periodic flume with a paddle and a damping zone, 1 and {n} processes")
mirror_case = os.path.join(WORK, "dambreak_mirror.yaml")
with open(os.path.join(CASES, "demo_dambreak.yaml")) as f:
    text = f.read()
with open(mirror_case, "w") as f:
    f.write(text.replace("max: [0.584, 0.1, 1.0]}", "max: [0.584, 0.1, 1.0], symmetry: [xmax]}")
            .replace("open: [zmax]", "open: [zmax, xmax]"))
assert "symmetry: [xmax]" in open(mirror_case).read()
mir = runs_on([1, 3], "dambreak_mirror", mirror_case, ["--set", "time.end=0.03", "--set", "time.output_every=0.015"])
same_files(mir[1], mir[3], "dam break with a symmetry plane across the slabs, 1 and 3 processes")
# laminar_sps: the stress each particle carries travels with it (exchanges, halo copies,
# mirror images, checkpoints): 1 and 3 processes, and written by 3, continued by 2
sps_sets = ["--set", "time.end=0.03", "--set", "time.output_every=0.015", "--set", "sph.viscosity=laminar_sps"]
sps = runs_on([1, 3], "dambreak_mirror_sps", mirror_case, sps_sets)
same_files(sps[1], sps[3], "dam break with laminar_sps and a symmetry plane, 1 and 3 processes")
out = os.path.join(WORK, "sps_restart")
r = mpi(3, ["run", mirror_case, "--out", out, "--quiet"] + sps_sets + ["--set", "time.end=0.015"])
r2 = mpi(2, ["restart", out, "--quiet", "--set", "time.end=0.03"])
check(r.returncode == 0 and r2.returncode == 0, f"laminar_sps: 3 processes to 0.015 s, 2 on to 0.03 s "
      f"(exits {r.returncode}, {r2.returncode}: {r2.stderr[-300:]})")
same_files(sps[1], out, "laminar_sps written by 3 processes, continued by 2, against 1 straight")

# Slabs along a periodic axis (a ring): water moving uniformly through a box periodic along
# every axis, and a flume periodic along its length (mDBC, symplectic) with a hump of water
# running across the face at 1 m/s: 1, 2 and 3 processes.
uniform_case = os.path.join(WORK, "uniform_all_periodic.yaml")
with open(uniform_case, "w") as f:
    f.write("""name: uniform_all_periodic
dp: 0.01
gravity: [0, 0, 0]
time: {end: 0.1, output_every: 0.05}
domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.1], periodic: [xmin, xmax, ymin, ymax, zmin, zmax]}
sph: {c0: 10, hmax: 0.1}
fluid: [{box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}, velocity: [0.5, 0.2, -0.1]}]
""")
ring_case = os.path.join(WORK, "ring_flume.yaml")
with open(ring_case, "w") as f:
    f.write("""name: ring_flume
dp: 0.01
time: {end: 0.05, output_every: 0.025, gauge_every: 0.005}
domain: {min: [0, 0, 0], max: [0.9, 0.06, 0.3], periodic: [xmin, xmax]}
sph: {boundary: mdbc, integrator: symplectic}
fluid:
  - {box: {min: [0, 0, 0], max: [0.9, 0.06, 0.08]}, velocity: [1, 0, 0]}
  - {box: {min: [0.8, 0, 0.08], max: [0.9, 0.06, 0.16]}, velocity: [1, 0, 0]}
walls: [{name: tank, box: {min: [0, 0, 0], max: [0.9, 0.06, 0.3]}, open: [zmax, xmin, xmax]}]
gauges:
  - {name: H0, type: height, x: 0.005, y: 0.03}
  - {name: P1, type: pressure, at: [0.895, 0.03, 0.02]}
""")
for name, case in (("uniform_all_periodic", uniform_case), ("ring_flume", ring_case)):
    rr = runs_on([1, 2, 3], name, case, [])
    for n in (2, 3):
        same_files(rr[1], rr[n], f"{name}: slabs along the periodic x axis, 1 and {n} processes")
    check(summary(rr[3])["distributed"]["axis"] == "x", f"{name}: slabs along x")

# A sphere sinking on the face of a box periodic along x and y (slabs along z): spheres
# and their body particles across a periodic face, 1 and 3 processes.
sphere_csv = os.path.join(WORK, "sphere_on_face.csv")
with open(sphere_csv, "w") as f:
    f.write("0, 0.06, 0.1, 0.015\n")
sink_case = os.path.join(WORK, "periodic_sinking.yaml")
sink_gauges = [("vz", 0, "vz"), ("fx", 0, "fx")]
with open(sink_case, "w") as f:
    f.write(sinking_case("periodic_sinking", [0, 0, 0], [0.12, 0.12, 0.2], ", periodic: [xmin, xmax, ymin, ymax]",
                         ["zmax", "xmin", "xmax", "ymin", "ymax"], sphere_csv, sink_gauges, (0.02, 0.01, 0.002), None))
sink = runs_on([1, 3], "periodic_sinking", sink_case, [])
same_files(sink[1], sink[3], "a sphere sinking on a periodic face, 1 and 3 processes")

# Two spheres touching on a symmetry plane, as the half y < 0.06 m (slabs along z): the
# sphere meets its own mirror image (DEM) in mirrored water, 1 and 3 processes.
half_csv = os.path.join(WORK, "sphere_at_mirror.csv")
with open(half_csv, "w") as f:
    f.write("0.06, 0.045, 0.1, 0.015\n")
mirror_case = os.path.join(WORK, "symmetric_sinking.yaml")
with open(mirror_case, "w") as f:
    f.write(sinking_case("symmetric_sinking", [0, 0, 0], [0.12, 0.06, 0.2], ", symmetry: [ymax]", ["zmax", "ymax"],
                         half_csv, sink_gauges, (0.02, 0.01, 0.002), None))
mirror_sink = runs_on([1, 3], "symmetric_sinking", mirror_case, [])
same_files(mirror_sink[1], mirror_sink[3], "a sphere touching its mirror image, sinking, 1 and 3 processes")

# --- bad input: every process stops, one message, exit 2, nothing written
r = mpi(2, ["run", os.path.join(CASES, "demo_dambreak.yaml"), "--out", os.path.join(WORK, "bad"), "--set", "dp=-1"])
check(r.returncode == 2, f"bad input on 2 processes exits 2 (got {r.returncode})")
check(r.stderr.count("error:") == 1, f"one error message, not one per process ({r.stderr.count('error:')})")
check(not os.path.exists(os.path.join(WORK, "bad")), "nothing written for bad input")

# --- divergence: every process stops at the same step with exit 3, outputs intact
out = os.path.join(WORK, "unstable")
r = mpi(2, ["run", os.path.join(CASES, "demo_dambreak.yaml"), "--out", out, "--set", "sph.cfl=8",
            "--set", "time.end=0.5", "--set", "time.output_every=0.01"])
check(r.returncode == 3, f"diverging run on 2 processes exits 3 (got {r.returncode}; {r.stderr[-200:]})")
check(r.returncode == 3 and summary(out)["status"] == "diverged", "summary records the divergence")

# --- Ctrl-C (mpirun passes SIGINT on as SIGTERM): every process stops, state written, exit 130
out = os.path.join(WORK, "interrupted")
cmd = [MPIRUN, "--oversubscribe", "-n", "2"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
p = subprocess.Popen(cmd + [SURGE, "run", os.path.join(CASES, "demo_dambreak.yaml"), "--out", out, "--threads", "1",
                            "--set", "time.end=100"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                     env=dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE"))
deadline = time.time() + 120
while time.time() < deadline and not os.path.exists(os.path.join(out, "summary.json")):
    time.sleep(0.2)
time.sleep(2.0)
p.send_signal(signal.SIGINT)
try:
    p.communicate(timeout=120)
except subprocess.TimeoutExpired:
    p.kill()
    p.communicate()
s = summary(out)
check(s["status"] == "interrupted", f"interrupted run's summary says so (status {s['status']}, mpirun exit "
      f"{p.returncode})")
check(s["steps"] > 0 and os.path.exists(os.path.join(out, "checkpoint.bin")), "its state is written")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
