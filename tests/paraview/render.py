"""Runs under ParaView's pvbatch (with a display, e.g. xvfb-run): opens an XDMF
file with one of ParaView's readers, colours it by FIELD on a white background
(particles as 4-pixel points), fits the camera and saves a PNG of W x H pixels.

usage: pvbatch render.py FILE.xmf legacy|xdmf3s|xdmf3t FIELD OUT.png [W H]
"""
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, ResetCamera, SaveScreenshot, Show, Xdmf3ReaderS,
                             Xdmf3ReaderT, XDMFReader)

path, kind, field, png = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
size = [int(sys.argv[5]), int(sys.argv[6])] if len(sys.argv) > 6 else [400, 300]
reader = {"legacy": lambda: XDMFReader(FileNames=[path]),
          "xdmf3s": lambda: Xdmf3ReaderS(FileName=[path]),
          "xdmf3t": lambda: Xdmf3ReaderT(FileName=[path])}[kind]()
times = list(reader.TimestepValues) if reader.TimestepValues else []
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = size
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:  # ParaView >= 5.10 takes the background from the colour palette unless told not to
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
if times:
    view.ViewTime = times[-1]
display = Show(reader, view)
info = reader.GetDataInformation()
if info.GetNumberOfCells() == info.GetNumberOfPoints() and info.GetDataSetTypeAsString() == "vtkUnstructuredGrid":
    display.SetRepresentationType("Points")
    display.PointSize = 4.0
association = "CELLS" if reader.CellData.GetArray(field) is not None else "POINTS"
ColorBy(display, (association, field))
display.RescaleTransferFunctionToDataRange(True, False)
ResetCamera(view)
SaveScreenshot(png, view, ImageResolution=size)
print("RENDERED " + png, flush=True)
