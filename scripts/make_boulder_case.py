"""Writes the block of cases/boulder_on_gravel.yaml (issue 34): a closed box mesh, normals
out, 6 cm long (x), 4 cm across (y), 4 cm high (z), centred at (0.1, 0.06, 0.1) m, the
free rigid body the spheres of a gravel bed stop (cases/boulder_block.stl)."""
import os

here = os.path.join(os.path.dirname(__file__), "..", "cases")
lo = (0.07, 0.04, 0.08)
hi = (0.13, 0.08, 0.12)


def main():
    c = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    # corners: index = x + 2 y + 4 z (0: low, 1: high)
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    with open(os.path.join(here, "boulder_block.stl"), "w") as f:
        f.write("solid boulder_block\n")
        for a, b, cc, d in faces:
            for tri in ((a, b, cc), (a, cc, d)):
                p = [c[i] for i in tri]
                u = [p[1][k] - p[0][k] for k in range(3)]
                v = [p[2][k] - p[0][k] for k in range(3)]
                n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
                ln = sum(x * x for x in n) ** 0.5
                f.write(f" facet normal {n[0] / ln:.6f} {n[1] / ln:.6f} {n[2] / ln:.6f}\n  outer loop\n")
                for q in p:
                    f.write(f"   vertex {q[0]:.6f} {q[1]:.6f} {q[2]:.6f}\n")
                f.write("  endloop\n endfacet\n")
        f.write("endsolid boulder_block\n")


if __name__ == "__main__":
    main()
