"""Runs under ParaView's pvbatch: opens an XDMF file with one of ParaView's
readers and prints what it found as one line 'PROBE <json>': the time steps,
the dataset class, cell and point counts, bounds, array names and components
and the integrals of ExtractSurface + IntegrateVariables (area and integrated
arrays) at the last time step.

With FIELD, also the centre and FIELD value of every cell (grids of at most
5000 cells), for comparing the cell-to-value mapping with the HDF5 file.

usage: pvbatch probe.py FILE.xmf legacy|xdmf3s|xdmf3t [FIELD]
"""
import json
import os
import sys

from paraview import servermanager
from paraview.simple import ExtractSurface, IntegrateVariables, Xdmf3ReaderS, Xdmf3ReaderT, XDMFReader

path, kind = os.path.abspath(sys.argv[1]), sys.argv[2]  # Xdmf3 mis-resolves HDF5 names next to a bare file name
reader = {"legacy": lambda: XDMFReader(FileNames=[path]),
          "xdmf3s": lambda: Xdmf3ReaderS(FileName=[path]),
          "xdmf3t": lambda: Xdmf3ReaderT(FileName=[path])}[kind]()
times = list(reader.TimestepValues) if reader.TimestepValues else []
t = times[-1] if times else 0.0
reader.UpdatePipeline(t)
data = servermanager.Fetch(reader)
blocks = 0
while data is not None and data.IsA("vtkCompositeDataSet"):
    blocks = data.GetNumberOfBlocks()
    data = data.GetBlock(0)


def arrays(a):
    return {a.GetArrayName(i): a.GetArray(i).GetNumberOfComponents() for i in range(a.GetNumberOfArrays())}


def ranges(a):
    return {a.GetArrayName(i): list(a.GetArray(i).GetRange(-1)) for i in range(a.GetNumberOfArrays())}


surface = IntegrateVariables(Input=ExtractSurface(Input=reader))
surface.UpdatePipeline(t)
integral = servermanager.Fetch(surface)
sums = {}
for attrs in (integral.GetCellData(), integral.GetPointData()):
    for i in range(attrs.GetNumberOfArrays()):
        sums[attrs.GetArrayName(i)] = attrs.GetArray(i).GetValue(0)
out = {"reader": kind, "times": times, "blocks": blocks, "class": data.GetClassName(),
       "cells": data.GetNumberOfCells(), "points": data.GetNumberOfPoints(), "bounds": list(data.GetBounds()),
       "cell_arrays": arrays(data.GetCellData()), "point_arrays": arrays(data.GetPointData()),
       "cell_ranges": ranges(data.GetCellData()), "point_ranges": ranges(data.GetPointData()), "integrals": sums}
if len(sys.argv) > 3 and data.GetNumberOfCells() <= 5000:
    values = data.GetCellData().GetArray(sys.argv[3])
    centres = []
    for i in range(data.GetNumberOfCells()):
        pts = data.GetCell(i).GetPoints()
        c = [sum(pts.GetPoint(k)[d] for k in range(pts.GetNumberOfPoints())) / pts.GetNumberOfPoints() for d in range(3)]
        centres.append(c)
    out["cell_centres"] = centres
    out["cell_values"] = [values.GetValue(i) for i in range(values.GetNumberOfTuples())] if values else []
print("PROBE " + json.dumps(out), flush=True)
