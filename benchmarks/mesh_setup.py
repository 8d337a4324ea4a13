#!/usr/bin/env python3
"""Set-up time with a detailed closed STL body (issue 34): `surge check` of a 2 x 1 x 1 m
tank, water 0.5 m deep, around a closed UV sphere (radius 0.15 m, centre (1, 0.5, 0.25))
of about 8,000 or 100,000 triangles, at dp = 5 and 2.5 cm, one thread. Prints the wall
time (and CPU time: the machine may be shared) and the particle counts (which must not depend on how fast they were found).

usage: benchmarks/mesh_setup.py SURGE [WORKDIR]"""
import math
import os
import subprocess
import sys
import time

SURGE = sys.argv[1]
WORK = sys.argv[2] if len(sys.argv) > 2 else "/tmp/surge_mesh_setup"
os.makedirs(WORK, exist_ok=True)


def sphere(path, n):
    c, R = (1.0, 0.5, 0.25), 0.15

    def v(i, j):
        th, ph = math.pi * i / n, 2 * math.pi * j / n
        return (c[0] + R * math.sin(th) * math.cos(ph), c[1] + R * math.sin(th) * math.sin(ph), c[2] + R * math.cos(th))

    tris = []
    for i in range(n):
        for j in range(n):
            a, b, cc, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
            if i > 0:
                tris.append((a, b, d))
            if i < n - 1:
                tris.append((b, cc, d))
    with open(path, "w") as f:
        f.write("solid s\n")
        for t in tris:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for p in t:
                f.write("   vertex %.7f %.7f %.7f\n" % p)
            f.write("  endloop\n endfacet\n")
        f.write("endsolid s\n")
    return len(tris)


CASE = """name: mesh_setup
dp: {dp}
time: {{end: 0.01, output_every: 0.01}}
domain: {{min: [0, 0, 0], max: [2, 1, 1]}}
fluid:
  - box: {{min: [0, 0, 0], max: [2, 1, 0.5]}}
walls:
  - name: tank
    box: {{min: [0, 0, 0], max: [2, 1, 1]}}
    open: [zmax]
  - name: body
    mesh: {mesh}
    solid: true
"""
for n in (64, 224):
    mesh = os.path.join(WORK, f"sphere_{n}.stl")
    tris = sphere(mesh, n)
    for dp in (0.05, 0.025):
        case = os.path.join(WORK, f"case_{n}_{dp}.yaml")
        open(case, "w").write(CASE.format(dp=dp, mesh=mesh))
        t0, c0 = time.time(), os.times()
        r = subprocess.run([SURGE, "check", case], capture_output=True, text=True,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        line = [x for x in r.stdout.splitlines() if x.startswith("particles")]
        c1 = os.times()
        cpu = c1.children_user + c1.children_system - c0.children_user - c0.children_system
        print(f"{tris:7d} triangles, dp = {dp}: {time.time() - t0:6.2f} s wall, {cpu:6.2f} s CPU  "
              f"{line[0] if line else r.stderr[-200:]}")
