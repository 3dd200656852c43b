"""Opens an atssim XDMF sidecar in ParaView, steps to a frame and renders it.

Run with ParaView's own Python under a virtual X server (Debian's ParaView
5.11 has no EGL/OSMesa build, so --force-offscreen-rendering alone crashes):

    scripts/render_paraview.sh OUT.xdmf --frame 60 -o frame.png

which installs ParaView and Xvfb when missing and runs
`scripts/with_xvfb.sh pvpython scripts/paraview_render.py …`. Prints
one JSON line: time steps, points, cells by type, bounds, the time shown.
Exit 1 when the frame has no points or no cells (what ParaView showed before
issue #15).
"""
import argparse
import json
import os
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetDisplayProperties, OpenDataFile, ResetCamera,
                             SaveScreenshot, Show)

VTK_TRIANGLE, VTK_TETRA = 5, 10


def cell_counts(reader):
    """Cells of the shown frame by type, counted on the data itself."""
    data = servermanager.Fetch(reader)
    counts = {"triangles": 0, "tetrahedra": 0, "other": 0}
    blocks = [data]
    if data.IsA("vtkCompositeDataSet"):
        it = data.NewIterator()
        it.InitTraversal()
        blocks = []
        while not it.IsDoneWithTraversal():
            blocks.append(it.GetCurrentDataObject())
            it.GoToNextItem()
    for block in blocks:
        for i in range(block.GetNumberOfCells()):
            t = block.GetCellType(i)
            key = "triangles" if t == VTK_TRIANGLE else "tetrahedra" if t == VTK_TETRA else "other"
            counts[key] += 1
    return counts


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("xdmf")
    p.add_argument("--frame", type=int, default=-1, help="frame index (default: the last)")
    p.add_argument("-o", "--output", required=True, help="PNG to write")
    p.add_argument("--size", default="800x600")
    a = p.parse_args()

    # ParaView 5.11's XDMF 3 reader resolves the HDF5 file against the XDMF's
    # folder, but for a bare relative name ("run.xdmf") it uses the name
    # itself as the folder ("run.xdmfrun.h5"): always hand it a full path.
    reader = OpenDataFile(os.path.abspath(a.xdmf))
    if reader is None:
        sys.exit(f"paraview_render: ParaView cannot open {a.xdmf}")
    times = list(reader.TimestepValues or [0.0])
    t = times[a.frame]
    width, height = (int(v) for v in a.size.split("x"))
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [width, height]
    view.ViewTime = t
    view.OrientationAxesVisibility = 0
    reader.UpdatePipeline(t)
    display = Show(reader, view)
    ColorBy(display, ("CELLS", "object"))
    display.SetScalarBarVisibility(view, False)
    ResetCamera(view)
    camera = view.GetActiveCamera()
    camera.Elevation(25)
    camera.Azimuth(30)
    ResetCamera(view)
    SaveScreenshot(a.output, view, ImageResolution=[width, height])

    info = reader.GetDataInformation()
    report = {
        "xdmf": a.xdmf,
        "time_steps": len(times),
        "frame": a.frame if a.frame >= 0 else len(times) + a.frame,
        "time": t,
        "points": info.GetNumberOfPoints(),
        "cells": info.GetNumberOfCells(),
        **cell_counts(reader),
        "bounds": list(info.GetBounds()),
        "png": a.output,
    }
    print(json.dumps(report))
    if report["points"] == 0 or report["cells"] == 0:
        sys.exit("paraview_render: the frame has no points or no cells")


if __name__ == "__main__":
    main()
