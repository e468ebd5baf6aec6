"""Run by pvpython (ParaView's Python, a real ParaView client): reads CASE/vtk/case.pvd and every
dataset it lists with ParaView's readers (a .pvtu's pieces appended into one grid), and prints them as
JSON for rkpost_paraview.py and partitioned_output.py to compare."""
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from paraview import servermanager as sm
from paraview.simple import PVDReader, XMLPartitionedUnstructuredGridReader, XMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

vtk_dir = Path(sys.argv[1]) / "vtk"
series = PVDReader(FileName=str(vtk_dir / "case.pvd"))
series.UpdatePipelineInformation()
series.UpdatePipeline()
blocks = sm.Fetch(series)  # the blocks' names, as ParaView's pipeline browser shows them
out = {"times": list(series.TimestepValues), "datasets": [],
       "blocks": [blocks.GetMetaData(i).Get(blocks.NAME()) for i in range(blocks.GetNumberOfBlocks())]
       if blocks.IsA("vtkMultiBlockDataSet") else []}  # one part alone (no dies): a grid, no blocks
for d in ET.parse(vtk_dir / "case.pvd").getroot().iter("DataSet"):
    path = vtk_dir / d.get("file")
    reader = XMLPartitionedUnstructuredGridReader if path.suffix == ".pvtu" else XMLUnstructuredGridReader
    grid = sm.Fetch(reader(FileName=[str(path)]))
    pd, cd = grid.GetPointData(), grid.GetCellData()
    entry = {"file": d.get("file"), "part": int(d.get("part")), "time": float(d.get("timestep")),
             "points": vtk_to_numpy(grid.GetPoints().GetData()).tolist(),
             "cells": grid.GetNumberOfCells(),
             "cell_types": sorted({grid.GetCellType(c) for c in range(grid.GetNumberOfCells())}),
             # each cell's points: connectivity[offsets[c]:offsets[c + 1]]
             "connectivity": vtk_to_numpy(grid.GetCells().GetConnectivityArray()).tolist(),
             "offsets": vtk_to_numpy(grid.GetCells().GetOffsetsArray()).tolist(),
             "point_data": {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)).tolist() for k in range(pd.GetNumberOfArrays())},
             "cell_data": {cd.GetArrayName(k): vtk_to_numpy(cd.GetArray(k)).tolist() for k in range(cd.GetNumberOfArrays())}}
    out["datasets"].append(entry)
print(json.dumps(out))
