#!/usr/bin/env python3
"""The water asked for (issue 35): every shipped case's fluid boxes hold their own volume
(surge check's 'water ... placed of ...') within 0.5 %, at the case's dp and at 3 cm
(boxes that walls or bodies cut are skipped: they hold less on purpose);
with fill: lattice a box that is not a whole number of spacings holds less (the old
placement, kept on request). Cases without fluid boxes (DEM only, reservoirs) are skipped.

Usage: test_water_volume.py SURGE CASES_DIR"""
import glob
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import Checks  # noqa: E402

SURGE, CASES = sys.argv[1], sys.argv[2]
checks = Checks(SURGE, "")
PLACED = re.compile(r"water\s+([0-9.e+-]+) m\^3 placed of ([0-9.e+-]+) m\^3")


DROPPED = re.compile(r"(\d+) fluid particles dropped inside walls")


def placed(case, *extra):
    """(placed, asked) in m^3, or None without fluid boxes, with water dropped inside walls
    (a slope or a body in the box: less is placed on purpose) or where the case cannot
    run at that dp (a periodic slab narrower than 4 h)."""
    r = subprocess.run([SURGE, "check", case, *extra], capture_output=True, text=True)
    name = f"{os.path.basename(case)} {' '.join(extra)}"
    if r.returncode == 2 and "a periodic length must be at least" in r.stderr:
        print(f"skip {name}: its periodic slab is narrower than 4 h at this dp")
        return None
    checks.check(r.returncode == 0, f"{name}: surge check (exit {r.returncode}: {r.stderr.strip()[:200]})")
    d = DROPPED.search(r.stdout)
    if d and int(d.group(1)) > 0:
        print(f"skip {name}: {d.group(1)} fluid particles dropped inside walls")
        return None
    m = PLACED.search(r.stdout)
    return (float(m.group(1)), float(m.group(2))) if m else None


seen = 0
for case in sorted(glob.glob(os.path.join(CASES, "*.yaml"))):
    for extra in ([], ["--set", "dp=0.03"]):
        v = placed(case, *extra)
        if v is None:
            continue  # no fluid box
        seen += 1
        share = v[0] / v[1]
        checks.check(abs(share - 1) <= 0.005, f"{os.path.basename(case)} {' '.join(extra) or '(its dp)'}: "
                                               f"{v[0]:.6g} m^3 placed of {v[1]:.6g} m^3 ({100 * share:.2f} %)")
checks.check(seen >= 8, f"{seen} case runs compared")
# The old placement, on request: SPHERIC's column at 3 cm held 95.0 % of its box.
spheric = os.path.join(CASES, "spheric_test2.yaml")
v = placed(spheric, "--set", "dp=0.03", "--set", "fluid.0.fill=lattice")
checks.check(v is not None and abs(v[0] / v[1] - 0.950) < 0.001,
             f"spheric_test2 at 3 cm with fill: lattice holds {100 * v[0] / v[1]:.1f} % (95.0 % before exact fill)")
checks.finish("water volume")
