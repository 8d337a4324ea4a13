#!/usr/bin/env python3
"""Water against theory (issue 35): each part starts from a state written particle by
particle (fluid[].particles) and compares a run with a closed form.

1. Standing wave: the first sloshing mode of a closed tank 0.15 m long (CI; 0.3 m for
   --long's report), 0.15 m deep (30 dp at dp = 5 mm), a slab periodic across, the water
   level and moving with the mode's velocity field for an amplitude a = 0.04 depth. With
   laminar viscosity, fickian shifting and h = 2 dp: the period from the gauges' zero crossings within 1 % of
   omega^2 = g k tanh(k h) and the decay per period (the frames' velocities projected on
   the mode, fitted by a damped cosine) at most 2 %. At the default h = 1.2 dp the decay
   is about 10 % (--open).
2. Taylor-Green vortex at Re = 100: u = U sin(2 pi x/L) cos(2 pi y/L), v = -U cos sin,
   periodic in x, y and a thin z; no walls, no gravity. The velocity amplitude (from the
   frames: the particles' velocities projected on the initial field) decays as
   exp(-8 pi^2 nu t / L^2) within 5 % over one decay time with laminar viscosity and
   delta_plus shifting (A = 10, h = 2 dp); the other settings' figures are printed.
3. Still water with shifting on: pressure within 1 % of rho g d after 2 s, the surface
   where it started (within dp/4), nothing removed. Checked for fickian shifting;
   delta_plus (A = 10), whose shift does not scale with the velocity, lifts the surface
   and fails (checked with --open only; docs/validation.md).

4. Solitary wave (Boussinesq profile, A/h = 0.2, h = 0.1 m, 20 dp per depth, the velocity
   field from the profile) over 15 depths of flat channel: celerity within 2 % of
   sqrt(g (h + A)), height loss at most 5 % with laminar viscosity and fickian shifting
   (only with --part solitary: ctest waves_solitary, label long).

Usage: test_waves.py SURGE WORK [--long [--only LABEL,...]] [--open] [--reuse] [--part standing|taylor_green|hydrostatic|solitary]
Every run names its viscosity and shifting: the figures do not move with the defaults.
--long also runs the other settings, whose figures are printed, not checked; --open also
checks what surge does not meet yet: the standing wave's decay at h = 1.2 dp (2 % per
period; about 10 %) and still water under delta_plus shifting (docs/validation.md)."""
import math
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import Checks  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import surge_post  # noqa: E402

SURGE, WORK = sys.argv[1], sys.argv[2]
LONG = "--long" in sys.argv  # also the settings that are only reported
OPEN = "--open" in sys.argv  # also the targets not met yet (ctest label open): the standing wave's decay
PART = sys.argv[sys.argv.index("--part") + 1] if "--part" in sys.argv else None
# --only LABEL,...: of the solitary rows (laminar_fickian and --long's), only these (about 40 minutes each)
ONLY = sys.argv[sys.argv.index("--only") + 1].split(",") if "--only" in sys.argv else None
# --reuse: WORK is kept, and a run whose folder there says it completed is read, not run
# again (a report's long runs continued with `surge restart` across sessions).
REUSE = "--reuse" in sys.argv
if not REUSE:
    shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK, exist_ok=True)
checks = Checks(SURGE, WORK, reuse=REUSE)
check = checks.check
G, RHO0, GAMMA = 9.81, 1000.0, 7.0


def tait_density(p, c0):
    """The density at pressure p (the EOS of SPEC 2.2, B = c0^2 rho0 / gamma)."""
    b = c0 * c0 * RHO0 / GAMMA
    return RHO0 * (1 + p / b) ** (1 / GAMMA)


def write_table(name, pos, vel, rho):
    path = os.path.join(WORK, name + ".csv")
    np.savetxt(path, np.column_stack([pos, vel, rho]), fmt="%.9g", delimiter=",", header="x,y,z,vx,vy,vz,rho",
               comments="")
    return path


# ---------------------------------------------------------------- 1. standing wave
DP, DEPTH = 0.005, 0.15
C0 = 10 * math.sqrt(G * DEPTH)  # the wave's speeds are 0.06 m/s: Ma below 0.01


class Tank:
    """A closed tank `length` long holding DEPTH of water, its first sloshing mode of
    amplitude a = 0.04 depth: wave number k = pi / length, omega^2 = g k tanh(k h)."""

    def __init__(self, length):
        self.length = length
        self.amp = 0.04 * DEPTH
        self.k = math.pi / length
        self.omega = math.sqrt(G * self.k * math.tanh(self.k * DEPTH))
        self.period = 2 * math.pi / self.omega

    def mode_velocity(self, pos):
        """The mode's velocity field for a unit velocity amplitude (state's, at t = 0)."""
        x, z = pos[:, 0], pos[:, 2]
        k = self.k
        return np.column_stack([-np.cosh(k * z) * np.sin(k * x), np.zeros(len(x)), np.sinh(k * z) * np.cos(k * x)])

    def state(self, width):
        """The water at rest on a lattice of dp, hydrostatic, moving as the standing wave
        eta = a cos(k x) sin(omega t) does at t = 0 (its surface flat): potential
        phi = (a omega / k) cosh(k z) / sinh(k h) cos(k x) cos(omega t), u = grad phi.
        (A surface displaced instead needs columns of other spacings than dp, whose particle
        volumes m / rho then disagree with their spacing: the water's mass stays level.)"""
        nx, ny, nz = round(self.length / DP), round(width / DP), round(DEPTH / DP)
        i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
        pos = np.column_stack([(i.ravel() + 0.5) * DP, (j.ravel() + 0.5) * DP, (k.ravel() + 0.5) * DP])
        vel = self.amp * self.omega / math.sinh(self.k * DEPTH) * self.mode_velocity(pos)
        rho = tait_density(RHO0 * G * (DEPTH - pos[:, 2]), C0)
        return pos, vel, rho

    def case(self, name, table, sph, periods, width):
        length = self.length
        return f"""name: {name}
dp: {DP}
time: {{end: {periods * self.period:.5f}, output_every: {self.period / 16:.5f}, gauge_every: 0.004}}
gravity: [0, 0, -9.81]
domain: {{min: [0, 0, 0], max: [{length}, {width}, 0.19], periodic: [ymin, ymax]}}
sph: {{c0: {C0:.6f}, boundary: mdbc, integrator: symplectic, {sph}}}
fluid: [{{particles: {table}}}]
walls: [{{name: tank, box: {{min: [0, 0, 0], max: [{length}, {width}, 0.19]}}, open: [ymin, ymax, zmax]}}]
gauges:
  - {{name: left, type: height, x: 0.01, y: {width / 2}}}
  - {{name: right, type: height, x: {length - 0.01}, y: {width / 2}}}
"""

    def mode_amplitude(self, frame):
        """The frame's velocities projected on the mode: least squares over its particles."""
        u = self.mode_velocity(frame["position"].astype(np.float64))
        return np.sum(frame["velocity"].astype(np.float64) * u) / np.sum(u * u)


# The tank of the reported settings (kh = pi / 2) and CI's deep one (kh = pi: half the
# water and two thirds of the period, a third of the cost; its bottom barely moves).
SHALLOW, DEEP = Tank(0.3), Tank(0.15)


def slab_width(h_over_dp):
    """The periodic slab's width: 5 spacings, or two kernel supports (4 h) if wider."""
    return DP * max(5, 2 * math.ceil(2 * h_over_dp))


def damped_cosine_rate(t, q, omega):
    """The rate lam of the fit q = exp(-lam t) (a cos(w t) + b sin(w t)), Gauss-Newton from
    lam = 0 and the linear theory's w = omega."""
    x = np.array([q[0], 0.0, 0.0, omega])  # a, b, lam, w

    def model(x):
        e = np.exp(-x[2] * t)
        return e * (x[0] * np.cos(x[3] * t) + x[1] * np.sin(x[3] * t))

    for _ in range(50):
        r = q - model(x)
        jac = np.column_stack([(model(x + d) - model(x - d)) / (2 * d[d != 0][0])
                               for d in np.diag([1e-6, 1e-6, 1e-6, 1e-6])])
        step = np.linalg.lstsq(jac, r, rcond=None)[0]
        x += step
        if np.all(np.abs(step) < 1e-12):
            break
    return x[2]


def crossings(t, eta):
    """Times where eta crosses its mean, linearly interpolated."""
    e = eta - eta.mean()
    k = np.nonzero(np.sign(e[:-1]) * np.sign(e[1:]) < 0)[0]
    return t[k] - e[k] * (t[k + 1] - t[k]) / (e[k + 1] - e[k])


def standing_wave(label, sph, periods, limit_decay, h_over_dp=1.2, tank=SHALLOW):
    width = slab_width(h_over_dp)
    table = write_table("standing_%g_%g" % (tank.length, h_over_dp), *tank.state(width))
    out = checks.run("standing_" + label, tank.case("standing_" + label, table,
                                                    f"h_over_dp: {h_over_dp}, {sph}", periods, width))
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    s = surge_post.read_summary(os.path.join(out, "summary.json"))
    check(s["removed"]["total"] == 0, f"{label}: no water removed ({s['removed']})")
    t = g["time"]
    # left - right: the mode's antisymmetric part, twice the amplitude at each gauge
    eta = (g["left"] - g["right"]) / 2
    z = crossings(t, eta)
    period = 2 * np.mean(np.diff(z))
    err = period / tank.period - 1
    # The decay from the mode's own amplitude: each frame's velocities projected on the
    # mode's field (Tank.state), fitted with a damped cosine. The kinetic energy would
    # also count the lattice's settling noise, which at these speeds (0.03 m/s) holds more
    # energy than the wave by half a period and decays on its own.
    q = np.array([(time, tank.mode_amplitude(surge_post.read_vtp(f)))
                  for time, f in surge_post.read_pvd(os.path.join(out, "fluid.pvd"))])
    decay = 1 - math.exp(-damped_cosine_rate(q[:, 0], q[:, 1], tank.omega) * tank.period)
    peak = np.abs(eta[t <= tank.period / 2]).max()
    a0 = tank.amp * math.cos(tank.k * 0.01)  # at the gauges
    print(f"  {label}: period {period:.4f} s against {tank.period:.4f} s ({100 * err:+.2f} %), first crest "
          f"{peak * 1000:.2f} mm of {a0 * 1000:.2f} mm, amplitude decay {100 * decay:.2f} % per period (the mode's "
          f"velocity amplitude in {len(q)} frames over {periods} periods)", flush=True)
    check(abs(err) < 0.01, f"{label}: period within 1 % of linear theory ({100 * err:+.2f} %)")
    check(abs(peak / a0 - 1) < 0.05, f"{label}: first crest {peak * 1000:.2f} mm within 5 % of a = {a0 * 1000:.2f} mm")
    if limit_decay is not None:
        check(decay <= limit_decay, f"{label}: amplitude decays {100 * decay:.2f} % per period (at most "
                                    f"{100 * limit_decay:.0f} %)")
    return period, decay


# ---------------------------------------------------------------- 2. Taylor-Green vortex
TG_L, TG_U, TG_RE, TG_DP = 1.0, 1.0, 100.0, 0.02
TG_NU = TG_U * TG_L / TG_RE
TG_C0 = 10 * TG_U
TG_H = 2.0  # h / dp: at 1.2 the straining lattice (a spacing of 1.7 dp along the stretch by 0.1 s) breaks down
TG_THICK = 9 * TG_DP  # a periodic length of at least 4 h
TG_TIME = TG_L * TG_L / (8 * math.pi ** 2 * TG_NU)  # one decay time of the amplitude


def tg_field(pos):
    k = 2 * math.pi / TG_L
    x, y = pos[:, 0], pos[:, 1]
    u = np.column_stack([TG_U * np.sin(k * x) * np.cos(k * y), -TG_U * np.cos(k * x) * np.sin(k * y),
                         np.zeros(len(pos))])
    p = RHO0 * TG_U ** 2 / 4 * (np.cos(2 * k * x) + np.cos(2 * k * y))
    return u, p


def tg_state():
    n, nz = round(TG_L / TG_DP), round(TG_THICK / TG_DP)
    g = (np.arange(n) + 0.5) * TG_DP
    gz = (np.arange(nz) + 0.5) * TG_DP
    x, y, z = np.meshgrid(g, g, gz, indexing="ij")
    pos = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    u, p = tg_field(pos)
    return pos, u, tait_density(p, TG_C0)


def taylor_green(label, sph, limit):
    table = write_table("taylor_green", *tg_state())
    text = f"""name: tg_{label}
dp: {TG_DP}
time: {{end: {TG_TIME:.4f}, output_every: {TG_TIME / 8:.5f}}}
gravity: [0, 0, 0]
domain: {{min: [0, 0, 0], max: [{TG_L}, {TG_L}, {TG_THICK}], periodic: [xmin, xmax, ymin, ymax, zmin, zmax]}}
sph: {{c0: {TG_C0}, h_over_dp: {TG_H}, nu: {TG_NU}, integrator: symplectic, hydrostatic_init: false, {sph}}}
fluid: [{{particles: {table}}}]
"""
    out = checks.run("tg_" + label, text)
    frames = surge_post.read_pvd(os.path.join(out, "fluid.pvd"))
    worst, rows = 0.0, []
    for t, f in frames:
        d = surge_post.read_vtp(os.path.join(out, f))
        u0, _ = tg_field(d["position"].astype(np.float64))
        amp = np.sum(d["velocity"][:, :2] * u0[:, :2]) / np.sum(u0[:, :2] ** 2) * TG_U  # projection on the mode
        want = TG_U * math.exp(-8 * math.pi ** 2 * TG_NU * t / TG_L ** 2)
        worst = max(worst, abs(amp / want - 1))
        rows.append((t, amp, want))
    s = surge_post.read_summary(os.path.join(out, "summary.json"))
    print(f"  {label}: amplitude at t/T = 0.5, 1: " +
          ", ".join(f"{a:.4f} (theory {w:.4f})" for t, a, w in rows if abs(t / TG_TIME - 0.5) < 0.01 or
                    abs(t / TG_TIME - 1) < 0.01) + f"; largest deviation {100 * worst:.2f} %", flush=True)
    check(s["removed"]["total"] == 0, f"tg {label}: no water removed ({s['removed']})")
    if limit is not None:
        check(worst < limit, f"tg {label}: amplitude within {100 * limit:.0f} % of exp(-8 pi^2 nu t / L^2) over one "
                             f"decay time ({100 * worst:.2f} %)")
    return worst


# ---------------------------------------------------------------- 4. solitary wave
SOL_H, SOL_A, SOL_DP = 0.1, 0.02, 0.005  # A / h = 0.2, 20 dp per depth
SOL_LEN, SOL_WIDTH, SOL_X0 = 3.3, 0.025, 1.0
SOL_K = math.sqrt(3 * SOL_A / (4 * SOL_H ** 3))
SOL_C = math.sqrt(G * (SOL_H + SOL_A))
SOL_GAUGES = [SOL_X0 + 0.25 * i for i in range(7)]  # to 15 depths from the start
SOL_C0 = 12.0  # 11 c: Ma 0.09


def solitary_state():
    """Boussinesq's solitary wave eta = A sech^2(k (x - x0)), k = sqrt(3A / 4h^3), moving
    at c = sqrt(g (h + A)) (SPEC 8): each column of dp holds round((h + eta) / dp)
    particles, its spacing stretched to end at h + eta (the column's mass is its water's
    within half a spacing), u = c eta / (h + eta) over the depth, w = -z du/dx
    (continuity), the pressure hydrostatic below the column's surface."""
    pos, vel, rho = [], [], []
    nx, ny = round(SOL_LEN / SOL_DP), round(SOL_WIDTH / SOL_DP)
    for i in range(nx):
        x = (i + 0.5) * SOL_DP
        sech2 = 1 / math.cosh(SOL_K * (x - SOL_X0)) ** 2
        eta = SOL_A * sech2
        d = SOL_H + eta
        u = SOL_C * eta / d
        deta = -2 * SOL_K * eta * math.tanh(SOL_K * (x - SOL_X0))
        dudx = SOL_C * SOL_H * deta / (d * d)
        n = round(d / SOL_DP)
        s = d / n
        for m in range(n):
            z = (m + 0.5) * s
            for j in range(ny):
                pos.append((x, (j + 0.5) * SOL_DP, z))
                vel.append((u, 0.0, -z * dudx))
                rho.append(tait_density(RHO0 * G * (d - z), SOL_C0))
    return np.array(pos), np.array(vel), np.array(rho)


def solitary_case(name, table, sph):
    end = (SOL_GAUGES[-1] - SOL_X0) / SOL_C + 0.25
    gauges = "\n".join(f"  - {{name: g{i}, type: height, x: {x:.3f}, y: {SOL_WIDTH / 2}}}"
                       for i, x in enumerate(SOL_GAUGES))
    return f"""name: {name}
dp: {SOL_DP}
time: {{end: {end:.3f}, output_every: 0.5, gauge_every: 0.002}}
gravity: [0, 0, -9.81]
domain: {{min: [0, 0, 0], max: [{SOL_LEN}, {SOL_WIDTH}, 0.2], periodic: [ymin, ymax]}}
sph: {{c0: {SOL_C0}, boundary: mdbc, integrator: symplectic, {sph}}}
fluid: [{{particles: {table}}}]
walls: [{{name: channel, box: {{min: [0, 0, 0], max: [{SOL_LEN}, {SOL_WIDTH}, 0.2]}}, open: [ymin, ymax, zmax]}}]
gauges:
{gauges}
"""


def crest(t, eta):
    """The time and height of a gauge's highest sample, refined by the parabola through it
    and its two neighbours."""
    k = int(np.argmax(eta))
    if 0 < k < len(eta) - 1:
        a, b, c = eta[k - 1], eta[k], eta[k + 1]
        den = a - 2 * b + c
        off = 0.5 * (a - c) / den if den != 0 else 0.0
        return t[k] + off * (t[k + 1] - t[k]), b - 0.25 * (a - c) * off
    return t[k], eta[k]


def solitary(label, sph, checked):
    table = os.path.join(WORK, "solitary.csv")
    if not os.path.exists(table):
        write_table("solitary", *solitary_state())
    out = checks.run("solitary_" + label, solitary_case("solitary_" + label, table, sph))
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    s = surge_post.read_summary(os.path.join(out, "summary.json"))
    crests = [crest(g["time"], g["g%d" % i] - SOL_H) for i in range(len(SOL_GAUGES))]
    tc = np.array([c[0] for c in crests])
    hc = np.array([c[1] for c in crests])
    celerity = np.polyfit(tc[1:], SOL_GAUGES[1:], 1)[0]  # from the first gauge downstream of the start
    err = celerity / SOL_C - 1
    loss = 1 - hc[-1] / SOL_A
    print(f"  {label}: crest heights {', '.join('%.2f' % (1000 * h) for h in hc)} mm at x = "
          f"{', '.join('%.2f' % x for x in SOL_GAUGES)} m; celerity {celerity:.4f} m/s against "
          f"sqrt(g(h + A)) = {SOL_C:.4f} ({100 * err:+.2f} %); height loss over 15 depths {100 * loss:.1f} % of A "
          f"({100 * (1 - hc[-1] / hc[1]):.1f} % from the first gauge downstream); removed {s['removed']['total']}",
          flush=True)
    if checked:
        check(s["removed"]["total"] == 0, f"solitary {label}: no water removed ({s['removed']})")
        check(abs(err) < 0.02, f"solitary {label}: celerity within 2 % of sqrt(g (h + A)) ({100 * err:+.2f} %)")
        check(loss <= 0.05, f"solitary {label}: height loss over 15 depths at most 5 % ({100 * loss:.1f} %)")


# ---------------------------------------------------------------- 3. still water, shifting on
HYDRO = """name: hydro_NAME
dp: 0.01
time: {end: 2.0, output_every: 0.5, gauge_every: 0.01}
gravity: [0, 0, -9.81]
domain: {min: [0, 0, 0], max: [0.3, 0.06, 0.3], periodic: [ymin, ymax]}
sph: {boundary: mdbc, integrator: symplectic, viscosity: laminar, SHIFT}
fluid: [{box: {min: [0, 0, 0], max: [0.3, 0.06, 0.2]}}]
walls: [{name: tank, box: {min: [0, 0, 0], max: [0.3, 0.06, 0.3]}, open: [ymin, ymax, zmax]}]
gauges:
  - {name: p_mid, type: pressure, at: [0.15, 0.03, 0.1]}
  - {name: p_deep, type: pressure, at: [0.05, 0.03, 0.05]}
  - {name: H, type: height, x: 0.15, y: 0.03}
"""


def hydrostatic(name, shift):
    out = checks.run("hydro_" + name, HYDRO.replace("NAME", name).replace("SHIFT", shift))
    g = np.genfromtxt(os.path.join(out, "gauges.csv"), delimiter=",", names=True)
    late = g["time"] >= 1.8 - 1e-9
    for probe, depth in (("p_mid", 0.1), ("p_deep", 0.15)):
        p, want = g[probe][late].mean(), RHO0 * G * depth
        check(abs(p / want - 1) < 0.01, f"{name}: {probe} {p:.1f} Pa within 1 % of rho g d = {want:.1f} Pa "
                                        f"({100 * (p / want - 1):+.2f} %)")
    drift = g["H"][late].mean() - g["H"][g["time"] < 0.1].mean()
    check(abs(drift) < 0.0025, f"{name}: the surface moved {1000 * drift:+.2f} mm from 0 to 2 s (within dp/4)")
    s = surge_post.read_summary(os.path.join(out, "summary.json"))
    check(s["removed"]["total"] == 0, f"{name}: no water removed ({s['removed']})")


if PART in (None, "standing"):
    print("1. standing wave: linear theory period %.4f s (tank %g m), %.4f s (%g m)"
          % (SHALLOW.period, SHALLOW.length, DEEP.period, DEEP.length), flush=True)
    # The kernel decides the decay: at h = 1.2 dp (the default) the wave loses about 10 %
    # per period to particle noise whatever the viscosity, shifting, wall model,
    # integrator or resolution (30 or 60 dp per depth); at h = 2 dp 0.3 %
    # (docs/validation.md). CI: h = 2 dp in the deep tank, period and decay; --long: the
    # same in the 0.3 m tank and the other settings; --open: the decay at 1.2 dp.
    standing_wave("laminar_shifting_h2_deep", "viscosity: laminar, shifting: fickian", 2, 0.02, 2.0, DEEP)
    if OPEN:
        standing_wave("laminar_shifting", "viscosity: laminar, shifting: fickian", 2, 0.02)
    if LONG:
        standing_wave("laminar_shifting_h2", "viscosity: laminar, shifting: fickian", 2, 0.02, 2.0)
        standing_wave("laminar_h2", "viscosity: laminar, shifting: none", 2, None, 2.0)
        standing_wave("artificial_h2", "viscosity: artificial, shifting: none", 2, None, 2.0)
        standing_wave("laminar", "viscosity: laminar, shifting: none", 2, None)
        standing_wave("artificial", "viscosity: artificial, shifting: none", 2, None)
if PART in (None, "taylor_green"):
    print("2. Taylor-Green vortex, Re = %g: decay time %.3f s" % (TG_RE, TG_TIME), flush=True)
    taylor_green("laminar_delta_plus", "viscosity: laminar, shifting: delta_plus, shifting_coefficient: 10", 0.05)
    if LONG:
        taylor_green("laminar", "viscosity: laminar, shifting: none", None)
        taylor_green("laminar_fickian", "viscosity: laminar, shifting: fickian", None)
        taylor_green("laminar_delta_plus_4", "viscosity: laminar, shifting: delta_plus, shifting_coefficient: 4", None)
if PART in (None, "hydrostatic"):
    print("3. still water with shifting", flush=True)
    hydrostatic("fickian", "shifting: fickian")
    if OPEN:
        hydrostatic("delta_plus", "shifting: delta_plus, shifting_coefficient: 10")
if PART == "solitary":  # its own ctest (waves_solitary)
    print("4. solitary wave, A/h = %.1f: celerity %.4f m/s" % (SOL_A / SOL_H, SOL_C), flush=True)
    if ONLY is None or "laminar_fickian" in ONLY:
        solitary("laminar_fickian", "viscosity: laminar, shifting: fickian", True)
    if LONG:
        for label, sph in (("laminar", "viscosity: laminar, shifting: none"),
                           ("artificial", "viscosity: artificial, shifting: none"),
                           ("artificial_fickian", "viscosity: artificial, shifting: fickian"),
                           ("laminar_sps", "viscosity: laminar_sps, shifting: none"),
                           ("laminar_sps_fickian", "viscosity: laminar_sps, shifting: fickian"),
                           ("artificial_delta_plus", "viscosity: artificial, shifting: delta_plus"),
                           ("laminar_delta_plus", "viscosity: laminar, shifting: delta_plus"),
                           ("laminar_sps_delta_plus", "viscosity: laminar_sps, shifting: delta_plus")):
            if ONLY is None or label in ONLY:
                solitary(label, sph, False)
checks.finish("wave theory")
