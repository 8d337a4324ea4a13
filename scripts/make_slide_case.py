"""Writes the geometry of the paper's slide test (SPEC §7, "slide tsunami"), which the
paper does not give in full; every choice is ours and is listed here and in the case
files:

* tank 6.8 m long (x) and 1.0 m wide (y), floor z = 0; water (coupled case) 0.4 m deep;
* the slope at the x = 0 end rises from the floor at x_toe = 3.0 m at 27.1 degrees,
  across the full width: cases/slide_slope.stl (two triangles, normals up the slope);
* the slide: 522 spheres of r = 0.03 m, a compact block 29 spheres long (down the
  slope) x 9 across x 2 thick, on a square lattice of spacing 2r, touching the slope,
  centred across the tank, its front at the still-water line (z = 0.4 m):
  cases/slide_spheres.csv (x, y, z, r).
"""
import math
import os

here = os.path.join(os.path.dirname(__file__), "..", "cases")
theta = math.radians(27.1)
x_toe, width, r = 3.0, 1.0, 0.03
H = x_toe * math.tan(theta)
d = (math.cos(theta), 0.0, -math.sin(theta))  # down the slope
n = (math.sin(theta), 0.0, math.cos(theta))   # out of the slope
z_water = 0.4
x_front = x_toe - z_water / math.tan(theta)   # where the slope meets the still-water line

with open(os.path.join(here, "slide_slope.stl"), "w") as f:
    f.write("solid slope\n")
    for tri in [((0, 0, H), (x_toe, 0, 0), (x_toe, width, 0)), ((0, 0, H), (x_toe, width, 0), (0, width, H))]:
        f.write(f" facet normal {n[0]:.6f} 0 {n[2]:.6f}\n  outer loop\n")
        for v in tri:
            f.write(f"   vertex {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
        f.write("  endloop\n endfacet\n")
    f.write("endsolid slope\n")

n_along, n_across, n_thick = 29, 9, 2
gap = 1e-4  # start clear of the slope and of each other
y0 = width / 2 - n_across * r
with open(os.path.join(here, "slide_spheres.csv"), "w") as f:
    f.write("# 522 spheres of the slide block (scripts/make_slide_case.py); x, y, z, r\n")
    for i in range(n_along):
        for j in range(n_across):
            for k in range(n_thick):
                s = -(r + i * 2 * (r + gap))   # along the slope, from the front
                h = r + gap + k * 2 * (r + gap)  # off the slope
                p = [x_front + s * d[0] + h * n[0], y0 + r + j * 2 * r, z_water + s * d[2] + h * n[2]]
                f.write(f"{p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}, {r}\n")
print(f"slope top z = {H:.3f} m at x = 0; slide front at x = {x_front:.3f} m; {n_along * n_across * n_thick} spheres")
