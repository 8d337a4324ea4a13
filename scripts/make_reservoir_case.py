#!/usr/bin/env python3
"""Writes a synthetic site for cases/reservoir/: a winding valley dammed into a reservoir,
with a slide on one flank, as GeoTIFFs in a projected coordinate system (UTM zone 32N,
EPSG:32632, metres), so that the example needs no external data.

  pre_failure.tif       today's ground, the slide in place (what a survey gives)
  sliding_surface.tif   the ground beneath the slide: the pre-failure ground minus the
                        slide's thickness (equal to it elsewhere). The walls, for the water
                        and for the spheres, are this surface; the slide fills the space
                        between the two.

The site (x, y relative to the south-west corner 600000 E, 5100000 N; every choice ours):
* a valley along x, its axis winding y_c(x) = 100 + 25 sin(2 pi x / 400); a trapezoid
  cross-section with a 10 m flat bed and flanks of slope 0.6 (31 degrees) up to a plateau
  at 1060 m;
* the bed falls from 1030 m at x = 0 to 1000 m at the dam, so that the lake (level
  1022 m) ends at x = 91 m, inside the domain; the dam (x = 330..350 m, crest 1030 m,
  faces of slope 1.5) closes the valley; downstream the bed lies at 990 m;
* a closed basin high on the north flank (a cone, floor 1015 m at x = 80 m, y = 195 m,
  below the reservoir's level 1022 m; its rim towards the valley at 1033 m): it must stay
  dry, since it does not connect to the lake;
* the slide: a lens on the north flank centred 46 m from the axis at x = 250 m (its
  lower edge at the water line), 60 m along the valley, 36 m up the flank, 6 m thick at
  the centre (a paraboloid), about 5100 m^3.

usage: make_reservoir_case.py [OUT_DIR] [--cell M]   (default cases/reservoir, 4 m pixels)
"""
import argparse
import os

import numpy as np
from osgeo import gdal, osr

X0, Y0 = 600000.0, 5100000.0
LX, LY = 400.0, 200.0


def axis(x):
    return 100.0 + 25.0 * np.sin(2 * np.pi * x / 400.0)


def ground(x, y):
    """Ground elevation at relative coordinates (arrays)."""
    slope_y = 25.0 * 2 * np.pi / 400.0 * np.cos(2 * np.pi * x / 400.0)
    d = np.abs(y - axis(x)) / np.sqrt(1.0 + slope_y**2)  # distance from the axis, across it
    bed = np.where(x < 340.0, 1030.0 - 30.0 * np.minimum(x, 340.0) / 340.0, 990.0)
    z = np.minimum(bed + 0.6 * np.maximum(d - 5.0, 0.0), 1060.0)
    dam = 1030.0 - 1.5 * np.maximum(np.abs(x - 340.0) - 10.0, 0.0)
    z = np.maximum(z, np.minimum(dam, 1060.0))
    basin = 1015.0 + 0.8 * np.hypot(x - 80.0, y - 195.0)
    return np.minimum(z, basin)


def slide_thickness(x, y):
    u = (x - 250.0) / 30.0
    v = (y - (axis(x) + 46.0)) / 18.0  # 28 m .. 64 m from the axis: up the north flank
    return np.maximum(6.0 * (1.0 - u**2 - v**2), 0.0)


def write(path, z, cell):
    ny, nx = z.shape
    drv = gdal.GetDriverByName("GTiff")
    ds = drv.Create(path, nx, ny, 1, gdal.GDT_Float32)
    # North-up: the first row is the northern one; pixel centres at X0 + i cell.
    ds.SetGeoTransform((X0 - cell / 2, cell, 0.0, Y0 + (ny - 1) * cell + cell / 2, 0.0, -cell))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32632)
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(z[::-1, :].astype(np.float32))
    ds.GetRasterBand(1).SetNoDataValue(-9999.0)
    ds.FlushCache()
    ds = None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "cases", "reservoir"))
    ap.add_argument("--cell", type=float, default=4.0)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    xs = np.arange(0.0, LX + 1e-9, a.cell)
    ys = np.arange(0.0, LY + 1e-9, a.cell)
    x, y = np.meshgrid(xs, ys)
    z = ground(x, y)
    # float32 in the file: round here so that both surfaces hold the same values.
    z = z.astype(np.float32).astype(np.float64)
    write(os.path.join(a.out, "pre_failure.tif"), z, a.cell)
    write(os.path.join(a.out, "sliding_surface.tif"), z - slide_thickness(x, y), a.cell)
    vol = slide_thickness(x, y).sum() * a.cell**2
    print(f"wrote {a.out}/pre_failure.tif and sliding_surface.tif ({len(xs)} x {len(ys)} pixels of {a.cell} m); "
          f"slide volume {vol:.0f} m^3")


if __name__ == "__main__":
    main()
