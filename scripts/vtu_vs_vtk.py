"""rkpost's .vtu files against VTK's own writer (run with pvpython): reads CASE/vtk/frame_*.vtu with
VTK and writes them again with vtkXMLUnstructuredGridWriter (appended raw, zlib and none), printing
the wall time and the bytes of each way next to rkpost's bytes.

  pvpython scripts/vtu_vs_vtk.py CASE      (after rkpost CASE; time rkpost itself with `time`)"""
import glob
import os
import sys
import tempfile
import time

from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter

files = sorted(glob.glob(os.path.join(sys.argv[1], "vtk", "frame_*.vtu")))
grids = []
for f in files:
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(f)
    r.Update()
    grids.append(r.GetOutput())
print(f"rkpost: {len(files)} frames, {sum(os.path.getsize(f) for f in files)} bytes")
with tempfile.TemporaryDirectory() as tmp:
    for label, zlib in (("VTK writer, appended raw, zlib", True), ("VTK writer, appended raw, none", False)):
        t, size = time.perf_counter(), 0
        for k, g in enumerate(grids):
            w = vtkXMLUnstructuredGridWriter()
            w.SetInputData(g)
            w.SetFileName(os.path.join(tmp, f"{k}.vtu"))
            w.SetDataModeToAppended()
            w.EncodeAppendedDataOff()
            w.SetCompressorTypeToZLib() if zlib else w.SetCompressorTypeToNone()
            w.Write()
            size += os.path.getsize(os.path.join(tmp, f"{k}.vtu"))
        print(f"{label}: {time.perf_counter() - t:.3f} s, {size} bytes")
