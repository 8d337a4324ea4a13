"""Writes the geometry of cases/rigid_slide.yaml (issue 34): a rigid wedge sliding down a
35-degree slope into still water, the classic experiment of landslide tsunamis (Heinrich
1992; Grilli & Watts 2005 use a wedge on a rail), here quasi-2D and of our own sizes:

* tank 1.6 m long (x), 0.1 m wide (y), water h = 0.3 m deep;
* the slope rises from the floor at x_toe = 0.778 m towards x = 0 at 35 degrees, across the
  width (cases/rigid_slide_slope.stl, normals up), from z = 0 to z = 0.45 m;
* the wedge: a right triangle in x-z, its hypotenuse (0.15 m) on the slope, its top
  horizontal and its front vertical, its lowest corner 2 cm above the still water
  (cases/rigid_slide_wedge.stl, a closed prism across the width, normals out).
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


x_up = x_toe - z_top / math.tan(th)
with open(os.path.join(here, "rigid_slide_slope.stl"), "w") as f:
    f.write("solid slope\n")
    a, b, c, d = (x_up, 0, z_top), (x_toe, 0, 0), (x_toe, width, 0), (x_up, width, z_top)
    facet(f, a, b, c)  # normal up the slope (out of the ground)
    facet(f, a, c, d)
    f.write("endsolid slope\n")

zb = h + 0.02  # the wedge's lowest corner B, on the slope
xb = x_toe - zb / math.tan(th)
L = 0.15
xa, za = xb - L * math.cos(th), zb + L * math.sin(th)  # A, up the slope
xc, zc = xb, za  # C: above B, level with A
with open(os.path.join(here, "rigid_slide_wedge.stl"), "w") as f:
    f.write("solid wedge\n")
    A0, B0, C0 = (xa, 0, za), (xb, 0, zb), (xc, 0, zc)
    A1, B1, C1 = (xa, width, za), (xb, width, zb), (xc, width, zc)
    facet(f, A0, B0, C0)  # y = 0 side, normal -y (A, B, C run counterclockwise in x-z)
    facet(f, A1, C1, B1)  # y = width side, normal +y
    for p, q in ((A0, B0), (B0, C0), (C0, A0)):  # the three long faces, normals out
        p1 = (p[0], width, p[2])
        q1 = (q[0], width, q[2])
        facet(f, p, q1, q)
        facet(f, p, p1, q1)
    f.write("endsolid wedge\n")
print(f"toe x = {x_toe:.4f} m, wedge corners A ({xa:.4f}, {za:.4f}), B ({xb:.4f}, {zb:.4f}), C ({xc:.4f}, {zc:.4f})")
print(f"travel to the floor along the slope: {zb / math.sin(th):.4f} m")
