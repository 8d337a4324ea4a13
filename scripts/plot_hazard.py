#!/usr/bin/env python3
"""Plots a run's hazard maps over a hillshade of its terrain, with the slide's outline and
the run-up points (PNG).

usage: plot_hazard.py OUT_DIR [--map max_elevation|max_depth|max_speed|arrival_time|rise]
                              [--png FILE]

OUT_DIR is a surge output folder of a case with a `hazard` section: its case.yaml names
the terrain grid and the slide's grids, maps/ holds the GeoTIFFs and runup.csv. `rise`
(the default) is the highest surface above the still level. Needs python3-gdal,
numpy and matplotlib (Debian packages).
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402  (python3-yaml, a dependency of matplotlib's Debian package set)
from osgeo import gdal  # noqa: E402


def read(path):
    ds = gdal.Open(path)
    if ds is None:
        raise SystemExit(f"{path}: not a raster GDAL can read")
    a = ds.GetRasterBand(1).ReadAsArray().astype(float)
    nd = ds.GetRasterBand(1).GetNoDataValue()
    if nd is not None:
        a[a == nd] = np.nan
    gt = ds.GetGeoTransform()
    ny, nx = a.shape
    extent = (gt[0], gt[0] + nx * gt[1], gt[3] + ny * gt[5], gt[3])  # left, right, bottom, top
    return a, extent, gt


def hillshade(z, dx, dy, azimuth=315.0, altitude=45.0):
    gy, gx = np.gradient(z, dy, dx)
    slope = np.pi / 2 - np.arctan(np.hypot(gx, gy))
    aspect = np.arctan2(-gx, gy)
    az, alt = np.radians(azimuth), np.radians(altitude)
    return np.sin(alt) * np.sin(slope) + np.cos(alt) * np.cos(slope) * np.cos(az - aspect)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--map", default="rise",
                    choices=["rise", "max_elevation", "max_depth", "max_speed", "arrival_time"])
    ap.add_argument("--png")
    a = ap.parse_args()
    with open(os.path.join(a.out, "case.yaml")) as f:
        case = yaml.safe_load(f)
    terrain = next(w["terrain"] for w in case["walls"] if "terrain" in w)
    ground, g_ext, g_gt = read(terrain)
    name = "max_elevation" if a.map == "rise" else a.map
    m, m_ext, _ = read(os.path.join(a.out, "maps", name + ".tif"))
    still = case["hazard"]["still_level"]
    if a.map == "rise":
        m = m - still
    labels = {"rise": "highest surface above the still level [m]", "max_elevation": "highest surface [m]",
              "max_depth": "greatest depth [m]", "max_speed": "greatest depth-averaged speed [m/s]",
              "arrival_time": f"arrival of {case['hazard']['arrival_height']} m above the still level [s]"}

    fig, ax = plt.subplots(figsize=(10, 5.5))
    ax.imshow(hillshade(ground, g_gt[1], -g_gt[5]), extent=g_ext, cmap="gray", vmin=0, vmax=1)
    cs = ax.contour(np.linspace(g_ext[0], g_ext[1], ground.shape[1]), np.linspace(g_ext[3], g_ext[2], ground.shape[0]),
                    ground, levels=np.arange(np.floor(np.nanmin(ground) / 10) * 10, np.nanmax(ground) + 1, 10),
                    colors="k", linewidths=0.3, alpha=0.5)
    ax.clabel(cs, fontsize=6, fmt="%.0f")
    cmap = "viridis_r" if a.map == "arrival_time" else "turbo"
    im = ax.imshow(np.ma.masked_invalid(m), extent=m_ext, cmap=cmap, alpha=0.85, interpolation="nearest")
    fig.colorbar(im, ax=ax, label=labels[a.map], shrink=0.8)
    # The slide: where the pre-failure surface stands above the sliding surface.
    for pk in case.get("dem", {}).get("packs", []):
        if "between" not in pk:
            continue
        top, t_ext, _ = read(pk["between"]["top"])
        bottom, _, _ = read(pk["between"]["bottom"])
        ax.contour(np.linspace(t_ext[0], t_ext[1], top.shape[1]), np.linspace(t_ext[3], t_ext[2], top.shape[0]),
                   top - bottom, levels=[0.05], colors="saddlebrown", linewidths=2)
        ax.plot([], [], color="saddlebrown", lw=2, label="slide")
    runup = os.path.join(a.out, "maps", "runup.csv")
    if os.path.exists(runup):
        with open(runup) as f:
            for row in csv.DictReader(f):
                if row["x"]:
                    ax.plot(float(row["x"]), float(row["y"]), "r^", ms=9)
                    ax.annotate(f"{row['line']}: {float(row['above_still_level']):+.2f} m", (float(row["x"]), float(row["y"])),
                                textcoords="offset points", xytext=(6, 6), fontsize=8, color="darkred")
        ax.plot([], [], "r^", label="run-up: the waterline at the highest wetted ground")
    ax.set_xlim(m_ext[0], m_ext[1])
    ax.set_ylim(m_ext[2], m_ext[3])
    ax.set_xlabel("easting [m]")
    ax.set_ylabel("northing [m]")
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_title(f"{case['name']}: {labels[a.map]}, still level {still} m")
    ax.legend(loc="lower left", fontsize=8)
    png = a.png or os.path.join(a.out, "maps", a.map + ".png")
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
