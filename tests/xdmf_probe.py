"""xdmf_probe.py FILE.xmf: what ParaView's XDMF Reader sees in a sidecar
(run with pvpython by test_xdmf.py).  Prints one JSON object: the time
steps, and for the last time step of every block its points, cells and
the range of every array."""
import json
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader

r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
times = r.TimestepValues
times = sorted(times) if hasattr(times, "__len__") else [times]
out = {"times": times, "blocks": {}}
want = [float(t) for t in sys.argv[2:]] or times[-1:]
for t in want:
    r.UpdatePipeline(t)
    d = sm.Fetch(r)
    blocks = []
    if d.IsA("vtkCompositeDataSet"):
        it = d.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            blocks.append((it.GetCurrentMetaData().Get(d.NAME()),
                           it.GetCurrentDataObject()))
            it.GoToNextItem()
    else:
        blocks.append(("", d))
    for name, b in blocks:
        arrays = {}
        for data in (b.GetPointData(), b.GetCellData()):
            for i in range(data.GetNumberOfArrays()):
                a = data.GetArray(i)
                arrays[data.GetArrayName(i)] = list(a.GetRange(-1 if
                    a.GetNumberOfComponents() > 1 else 0))
        out["blocks"]["%s@%r" % (name, t)] = {
            "points": b.GetNumberOfPoints(), "cells": b.GetNumberOfCells(),
            "arrays": arrays}
print("XDMF-PROBE " + json.dumps(out))
