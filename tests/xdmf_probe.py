"""xdmf_probe.py READER FILE.xmf: what one of ParaView's XDMF readers sees
in a sidecar at every time step (run with pvpython by test_xdmf.py).
READER: "open" (paraview.simple.OpenDataFile, what File > Open does: the
Xdmf3 reader) or "legacy" (the XDMF Reader).  Prints one JSON object: the
reader, the time steps, and for every time step and block its points,
cells, the sums of the point coordinates x and y, and every array's
minimum, maximum and sum.  A block is named by what it holds (film, balls,
particles, mac_cells, mac_u, mac_v, mac_markers): Xdmf3 drops the names
of grids."""
import json
import os
import sys

from paraview import servermanager as sm
from paraview.simple import OpenDataFile, XDMFReader
from vtk.numpy_interface import dataset_adapter as dsa

KINDS = [("radius", "balls"), ("psi", "film"), ("vx", "particles"),
         ("p", "mac_cells"), ("u", "mac_u"), ("v", "mac_v"),
         ("density", "mac_markers")]

kind, path = sys.argv[1], os.path.abspath(sys.argv[2])
r = OpenDataFile(path) if kind == "open" else XDMFReader(FileNames=[path])
r.UpdatePipelineInformation()
times = r.TimestepValues
times = sorted(times) if hasattr(times, "__len__") else [times]
out = {"reader": r.GetXMLName(), "times": times, "steps": []}
for t in times:
    r.UpdatePipeline(t)
    d = sm.Fetch(r)
    blocks = []
    if d.IsA("vtkCompositeDataSet"):
        it = d.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            blocks.append(it.GetCurrentDataObject())
            it.GoToNextItem()
    else:
        blocks.append(d)
    step = {}
    for b in blocks:
        w = dsa.WrapDataObject(b)
        arrays = {}
        for data in (w.PointData, w.CellData):
            for name in data.keys():
                a = data[name]
                arrays[name] = [float(a.min()), float(a.max()),
                                float(a.sum())]
        n = b.GetNumberOfPoints()
        pts = [b.GetPoint(i) for i in range(n)]
        name = next((k for a, k in KINDS if a in arrays), "?%d" % len(step))
        step[name] = {"points": n, "cells": b.GetNumberOfCells(),
                      "x": sum(p[0] for p in pts),
                      "y": sum(p[1] for p in pts), "arrays": arrays}
    out["steps"].append(step)
print("XDMF-PROBE " + json.dumps(out))
