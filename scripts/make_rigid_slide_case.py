"""Writes the geometry of cases/rigid_slide.yaml (issue 34): a rigid wedge sliding down a
35-degree slope into still water, the classic experiment of landslide tsunamis (Heinrich
1992; Grilli & Watts 2005 use a wedge on a rail), here quasi-2D and of our own sizes:

* tank 1.6 m long (x), 0.1 m wide (y), water h = 0.3 m deep;
* the slope rises from the floor at x_toe = 0.778 m towards x = 0 at 35 degrees, across the
  width, from z = 0 to z = 0.45 m, and the ground under it is closed down to the floor and
  back to the tank's end (cases/rigid_slide_slope.stl, a prism, normals out);
* the wedge: a right triangle in x-z, its hypotenuse (0.15 m) parallel to the slope and
  GAP = 2 dp above it, its top horizontal and its front vertical, its lowest corner 2 cm
  (plus the gap) above the still water (cases/rigid_slide_wedge.stl, a closed prism across
  the width, normals out). The gap stands for the rollers or the film of water a
  laboratory wedge runs on: with the wedge's wall particles on the slope's, no water gets
  under it, its top and front carry the water's pressure and its face on the slope none,
  and the rail's friction grows until it stops (docs/validation.md). Two spacings let the
  water in (one is the wall models' own spacing, which water does not pass).
"""
import math
import os

here = os.path.join(os.path.dirname(__file__), "..", "cases")
th = math.radians(35.0)
h, width, x_toe = 0.3, 0.1, 0.3 / math.tan(math.radians(35.0)) + 0.35
z_top = 0.45


def facet(f, a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    ln = math.sqrt(sum(x * x for x in n))
    f.write(f" facet normal {n[0] / ln:.6f} {n[1] / ln:.6f} {n[2] / ln:.6f}\n  outer loop\n")
    for p in (a, b, c):
        f.write(f"   vertex {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}\n")
    f.write("  endloop\n endfacet\n")


def prism(f, poly):
    """A closed prism across the width from a convex polygon in x-z, counterclockwise
    (x right, z up): its two ends and a face per edge, normals out."""
    ends0 = [(x, 0, z) for x, z in poly]
    ends1 = [(x, width, z) for x, z in poly]
    for k in range(1, len(poly) - 1):
        facet(f, ends0[0], ends0[k], ends0[k + 1])  # y = 0 end, normal -y
        facet(f, ends1[0], ends1[k + 1], ends1[k])  # y = width end, normal +y
    for k in range(len(poly)):
        p0, q0 = ends0[k], ends0[(k + 1) % len(poly)]
        p1, q1 = ends1[k], ends1[(k + 1) % len(poly)]
        facet(f, p0, q1, q0)
        facet(f, p0, p1, q1)


x_up = x_toe - z_top / math.tan(th)
with open(os.path.join(here, "rigid_slide_slope.stl"), "w") as f:
    # The ground under the slope, closed (a bare slope surface left a pocket behind its top
    # edge, x < x_up, that the set-up filled with water counted inside the slope's wall).
    f.write("solid slope\n")
    prism(f, [(0, 0), (x_toe, 0), (x_up, z_top), (0, z_top)])
    f.write("endsolid slope\n")

GAP = 2 * 0.0125  # two spacings at the case's dp (12.5 mm)
zb = h + 0.02  # the wedge's lowest corner B, on the slope (before the gap)
xb = x_toe - zb / math.tan(th)
L = 0.15
xa, za = xb - L * math.cos(th), zb + L * math.sin(th)  # A, up the slope
xc, zc = xb, za  # C: above B, level with A
nx, nz = math.sin(th), math.cos(th)  # the slope's normal, out of the ground
xa, za, xb, zb, xc, zc = xa + GAP * nx, za + GAP * nz, xb + GAP * nx, zb + GAP * nz, xc + GAP * nx, zc + GAP * nz
with open(os.path.join(here, "rigid_slide_wedge.stl"), "w") as f:
    f.write("solid wedge\n")
    prism(f, [(xa, za), (xb, zb), (xc, zc)])
    f.write("endsolid wedge\n")
print(f"toe x = {x_toe:.4f} m, wedge corners A ({xa:.4f}, {za:.4f}), B ({xb:.4f}, {zb:.4f}), C ({xc:.4f}, {zc:.4f})")
print(f"travel until its lowest corner meets the floor: {zb / math.sin(th):.4f} m along the slope")
