#!/usr/bin/env python3
"""Compares two gauges.csv files of the same case (CPU build against GPU build).

usage: compare_gauges.py REF.csv OTHER.csv TOL

For every gauge column: the largest |other - ref| over the common rows, relative to the
largest |ref| of that column. Exit 0 when every column is within TOL, 1 otherwise.
The two builds differ only in rounding (fused multiply-adds, library sqrt), so over the
first steps the difference is float round-off that grows with time.
"""
import csv
import sys


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    head_a, a = read(sys.argv[1])
    head_b, b = read(sys.argv[2])
    if head_a != head_b:
        print(f"different gauges: {head_a} vs {head_b}")
        return 1
    tol = float(sys.argv[3])
    n = min(len(a), len(b))
    if n == 0 or any(abs(a[k][0] - b[k][0]) > 1e-12 for k in range(n)):
        print(f"rows do not line up in time ({len(a)} vs {len(b)} rows)")
        return 1
    worst = 0.0
    print(f"{n} rows, t = 0 .. {a[n - 1][0]:g} s")
    print("| gauge | max abs | max relative to the gauge's range |")
    print("|---|---|---|")
    for c in range(1, len(head_a)):
        scale = max(abs(r[c]) for r in a[:n]) or 1.0
        diff = max(abs(a[k][c] - b[k][c]) for k in range(n))
        worst = max(worst, diff / scale)
        print(f"| {head_a[c]} | {diff:.3g} | {diff / scale:.2e} |")
    ok = worst <= tol and len(a) == len(b)
    print(f"{'PASS' if ok else 'FAIL'}: worst {worst:.2e} (tolerance {tol:g}), rows {len(a)} / {len(b)}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
