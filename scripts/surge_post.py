"""Reading surge output for validation and tests.

VTK files are read with VTK's own Python reader (an implementation independent
of surge's writer); gauges.csv and summary.json with numpy / json.
"""
import json
import os
import xml.etree.ElementTree as ET

import numpy as np


def read_vtp(path):
    """Returns a dict of numpy arrays: position (n,3), velocity, density, pressure, kind, id."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        raise IOError(f"VTK could not read {path}")
    poly = reader.GetOutput()
    out = {}
    if poly.GetNumberOfPoints() > 0:
        out["position"] = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    else:
        out["position"] = np.zeros((0, 3))
    pd = poly.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        arr = pd.GetArray(k)
        out[arr.GetName()] = vtk_to_numpy(arr)
    return out


def read_vtp_lines(path):
    """Line cells of a .vtp (the bond network of DEM output) as an (n, 2) array of point indices."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    lines = reader.GetOutput().GetLines()
    if lines.GetNumberOfCells() == 0:
        return np.zeros((0, 2), dtype=int)
    raw = vtk_to_numpy(lines.GetData())  # legacy layout: 2, a, b, 2, c, d, ...
    return raw.reshape(-1, 3)[:, 1:]


def read_pvd(path):
    """[(time, absolute vtp path)] in time order."""
    root = ET.parse(path).getroot()
    base = os.path.dirname(path)
    items = [(float(d.get("timestep")), os.path.join(base, d.get("file"))) for d in root.iter("DataSet")]
    return sorted(items)


def read_frames(run, t0, t1, pvd="fluid.pvd"):
    """(time, read_vtp's fields) of a run's frames with t0 <= time <= t1, in time order."""
    for t, frame in read_pvd(os.path.join(run, pvd)):
        if t0 - 1e-9 <= t <= t1 + 1e-9:
            yield t, read_vtp(frame)


def read_gauges(path):
    """(names, array with one row per sample; column 0 is time)."""
    with open(path) as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return names, data


def read_summary(path):
    with open(path) as f:
        return json.load(f)


def surge_front(positions, dp, spray_fraction=0.0005):
    """Leading-edge x of the water: the particle centre beyond which only a small
    fraction of the particles lies (isolated droplets ahead of the front are ignored),
    plus dp/2, since a particle stands for a cube of water of side dp."""
    x = np.sort(positions[:, 0])
    if len(x) == 0:
        return 0.0
    k = max(0, len(x) - 1 - int(spray_fraction * len(x)))
    return x[k] + 0.5 * dp


def read_front_data(path):
    """Columns T, Z of a surge-front file in data/ (comment lines start with #)."""
    rows = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#") or line[0].isalpha():
                continue
            rows.append([float(v) for v in line.replace(",", " ").split()])
    return np.array(rows)


def read_run_dp(run):
    """The particle spacing a run used, from its case.yaml (every default filled in)."""
    with open(os.path.join(run, "case.yaml")) as f:
        return next(float(line.split(":")[1]) for line in f if line.startswith("dp:"))


def style_axes(ax, xlabel, ylabel):
    """Labels, grid and legend of one validation plot's axes."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend()


def finish_plot(fig, ax, xlabel, ylabel, png):
    """Labels, grid and legend of a one-axis validation plot, saved as PNG."""
    style_axes(ax, xlabel, ylabel)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
