"""Pictures of a case, rendered off-screen by ParaView from what rkpost wrote (CASE/vtk/case.pvd):
the deformed part coloured by equivalent plastic strain, with the dies, at chosen frames, and the
integration cells coloured by the rank that computes them (the seed's Figs. 8c, 13, 18).

  scripts/pvbatch_offscreen.sh scripts/pictures.py CASE [--frames 0,-1] [--size 900x700]
  (or xvfb-run -a pvbatch ...; plain pvbatch where a display exists)

Writes CASE/plots/part_ep_FFFFF.png and CASE/plots/part_rank_FFFFF.png."""
import argparse
import xml.etree.ElementTree as ET
from pathlib import Path

from paraview.simple import (ColorBy, GetColorTransferFunction, GetScalarBar, Render, ResetCamera,
                             SaveScreenshot, Show, XMLUnstructuredGridReader, CreateView, Delete)


def collection(case: Path):
    """(time, part, file) of every dataset of the .pvd, in its order."""
    root = ET.parse(case / "vtk" / "case.pvd").getroot()
    return [(float(d.get("timestep")), int(d.get("part")), case / "vtk" / d.get("file")) for d in root.iter("DataSet")]


def render(part_file, die_files, out, colour, title, size, legend=True):
    view = CreateView("RenderView")
    view.ViewSize = size
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    try:  # ParaView 5.11: white background needs the palette override
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    part = XMLUnstructuredGridReader(FileName=[str(part_file)])
    shown = Show(part, view)
    shown.Representation = "Surface With Edges" if colour[0] == "CELLS" else "Surface"
    shown.EdgeColor = [0.2, 0.2, 0.2]
    shown.Ambient, shown.Diffuse = 0.3, 0.8  # the faces turned from the headlight stay readable
    ColorBy(shown, colour)
    lut = GetColorTransferFunction(colour[1])
    lut.ApplyPreset("Rainbow Uniform" if colour[1] == "rank" else "Turbo", True)
    shown.RescaleTransferFunctionToDataRange(True, False)
    if legend:
        bar = GetScalarBar(lut, view)
        bar.Title = title
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        shown.SetScalarBarVisibility(view, True)
    for f in die_files:
        die = XMLUnstructuredGridReader(FileName=[str(f)])
        d = Show(die, view)
        d.AmbientColor = d.DiffuseColor = [0.6, 0.6, 0.65]
        d.Opacity = 0.35
    view.CameraPosition = [1, -1.4, 0.9]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    ResetCamera(view)
    Render(view)
    SaveScreenshot(str(out), view, ImageResolution=size)
    Delete(view)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", type=Path)
    ap.add_argument("--frames", default="0,-1", help="frame positions in the .pvd (negative: from the end)")
    ap.add_argument("--size", default="900x700")
    a = ap.parse_args()
    size = [int(v) for v in a.size.split("x")]
    items = collection(a.case)
    times = sorted({t for t, part, _ in items})
    out = a.case / "plots"
    out.mkdir(exist_ok=True)
    for k in sorted({int(v) % len(times) for v in a.frames.split(",")}):
        t = times[k]
        part = [f for tt, p, f in items if tt == t and p == 0][0]
        dies = [f for tt, p, f in items if tt == t and p > 0]
        stem = part.stem.replace("frame_", "")
        render(part, dies, out / f"part_ep_{stem}.png", ("POINTS", "eq_plastic_strain"),
               f"eq. plastic strain, t = {1e6 * t:.1f} us", size)
        render(part, [], out / f"part_rank_{stem}.png", ("CELLS", "rank"), "rank", size)
        print(f"pictures: {out}/part_ep_{stem}.png, part_rank_{stem}.png (t = {t:g} s)")


main()
