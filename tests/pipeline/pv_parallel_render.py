"""Run by `mpirun -np N pvbatch --symmetric` (every process runs this script): reads a .pvtu with
ParaView's parallel reader, each process its share of the pieces, says on one line per process what
it read (JSON: its partition, points, ghost points, cells, the ranks of its cells), and renders the part
coloured by plastic strain from 0 to TOP (one scale on every process, each of which would
otherwise scale to its own pieces), composited over the processes, into a PNG (written by process 0); with OUT.png "-" it only reads.
  pv_parallel_render.py FRAME.pvtu OUT.png TOP"""
import ctypes
import ctypes.util
import json
import sys
import time

from paraview import servermanager as sm
from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Render, ResetCamera, SaveScreenshot, Show,
                             XMLPartitionedUnstructuredGridReader)
from vtkmodules.util.numpy_support import vtk_to_numpy



def wait_for_display(seconds=20):
    """Under load Xvfb may not take connections yet when a process asks for its window, and VTK then
    aborts ("bad X server connection", 1 run in 6 on 2026-12-02): open the display until it answers."""
    x11 = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11"))
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    for _ in range(int(seconds / 0.1)):
        display = x11.XOpenDisplay(None)
        if display:
            x11.XCloseDisplay(display)
            return
        time.sleep(0.1)
    sys.exit(f"no X display answered within {seconds} s")


pvtu, png, top = sys.argv[1], sys.argv[2], float(sys.argv[3])
pm = sm.vtkProcessModule.GetProcessModule()
reader = XMLPartitionedUnstructuredGridReader(FileName=[pvtu])
reader.UpdatePipeline()
local = reader.GetClientSideObject().GetOutputDataObject(0)  # this process's pieces
ghost = local.GetPointData().GetArray("vtkGhostType")
cell_rank = local.GetCellData().GetArray("rank")
print("piece " + json.dumps({
    "process": pm.GetPartitionId(), "processes": pm.GetNumberOfLocalPartitions(),
    "points": local.GetNumberOfPoints(), "cells": local.GetNumberOfCells(),
    "ghost_points": int((vtk_to_numpy(ghost) & 1).sum()) if ghost else -1,
    "cell_ranks": sorted({int(v) for v in vtk_to_numpy(cell_rank)}) if cell_rank else []}), flush=True)


def render():
    wait_for_display()
    view = CreateView("RenderView")
    view.ViewSize = [640, 480]
    view.Background = [1, 1, 1]
    try:  # ParaView 5.11: white background needs the palette override
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    shown = Show(reader, view)
    ColorBy(shown, ("POINTS", "eq_plastic_strain"))
    lut = GetColorTransferFunction("eq_plastic_strain")
    lut.ApplyPreset("Turbo", True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(0.0, top)
    view.CameraPosition = [1, -1.4, 0.9]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[640, 480])


if png != "-":  # "-": the read alone, no display needed (the script ends normally: MPI finalizes)
    render()
