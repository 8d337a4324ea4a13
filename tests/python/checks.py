"""What the end-to-end tests share: named checks that print ok / FAIL and are counted,
a case written into the work folder and run, and the sinking-sphere case of the image
tests."""
import json
import os
import subprocess
import sys


class Checks:
    def __init__(self, surge, work, reuse=False):
        # reuse: a run whose output folder already holds a completed run is read as it is
        self.surge, self.work, self.failures, self.reuse = surge, work, [], reuse

    def check(self, cond, what):
        print(("ok   " if cond else "FAIL ") + what, flush=True)
        if not cond:
            self.failures.append(what)

    def run(self, name, text, *extra):
        """Writes `text` as WORK/name.yaml, runs it into WORK/name; stops the test if it fails."""
        case = os.path.join(self.work, name + ".yaml")
        out = os.path.join(self.work, name)
        if self.reuse and completed(out):
            print(f"     {name}: the completed run in {out} is read", flush=True)
            return out
        with open(case, "w") as f:
            f.write(text)
        r = subprocess.run([self.surge, "run", case, "--out", out, "--quiet", *extra], capture_output=True, text=True)
        self.check(r.returncode == 0, f"{name} runs (exit {r.returncode}: {r.stderr[-400:]})")
        if r.returncode != 0:
            sys.exit(1)
        return out

    def finish(self, what):
        if self.failures:
            print(f"{len(self.failures)} check(s) failed")
            sys.exit(1)
        print(f"all {what} checks passed")


def completed(out):
    """Whether the run folder `out` holds a run that reached its end (summary.json)."""
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f).get("status") == "completed"
    except (OSError, ValueError):
        return False


def sinking_case(name, lo, hi, faces, open_faces, csv, gauges, times=(0.1, 0.1, 0.005),
                 sph="{boundary: mdbc, integrator: symplectic}"):
    """Spheres (csv: x, y, z, r per line; density 2500) sinking in still water 0.15 m deep,
    dp 5 mm, in the tank lo-hi (lists of three) open at `open_faces`; `faces`: the domain's
    periodic or symmetry keys, like ", symmetry: [ymax]"; gauges: (name, sphere, component);
    times: end, output and gauge intervals; sph: the sph mapping, or None for the defaults."""
    box = f"{{min: {lo}, max: {hi}}}"
    water = f"{{min: {lo}, max: {[hi[0], hi[1], 0.15]}}}"
    text = f"""name: {name}
dp: 0.005
time: {{end: {times[0]}, output_every: {times[1]}, gauge_every: {times[2]}}}
gravity: [0, 0, -9.81]
domain: {{min: {lo}, max: {hi}{faces}}}
"""
    if sph:
        text += f"sph: {sph}\n"
    text += f"""fluid: [{{box: {water}}}]
walls: [{{name: tank, box: {box}, open: [{", ".join(open_faces)}]}}]
dem:
  materials: [{{name: sphere, density: 2500, E: 1.0e7, nu: 0.2, phi: 30, restitution: 0.5}}]
  packs: [{{csv: {csv}, material: sphere}}]
gauges:
"""
    return text + "".join(f"  - {{name: {n}, type: sphere, sphere: {k}, component: {q}}}\n" for n, k, q in gauges)
