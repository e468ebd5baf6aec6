"""Pictures of a case, rendered off-screen by ParaView from what rkpost wrote (CASE/vtk/case.pvd):
the deformed part coloured by equivalent plastic strain, with the dies, at chosen frames, by its
temperature where the material has one, and the integration cells coloured by the rank that
computes them (as Figs. 8c, 13 and 18 of Wang et al. 2007 show the partition).

  scripts/pvbatch_offscreen.sh scripts/pictures.py CASE [--frames 0,-1] [--size 900x700]
  (or xvfb-run -a pvbatch ...; plain pvbatch where a display exists)

Writes CASE/plots/part_ep_FFFFF.png, part_temperature_FFFFF.png (with a temperature) and
part_rank_FFFFF.png, and CASE/plots/pictures.json: each picture's field, time and colour scale as
ParaView drew it (a continuous field's [low, high], or the rank's categories)."""
import argparse
import json
import xml.etree.ElementTree as ET
from pathlib import Path

from paraview.simple import (ColorBy, GetColorTransferFunction, GetScalarBar, Render, ResetCamera,
                             SaveScreenshot, Show, XMLPartitionedUnstructuredGridReader, XMLUnstructuredGridReader, CreateView,
                             Delete)


def collection(case: Path):
    """(time, part, file) of every dataset of the .pvd, in its order."""
    root = ET.parse(case / "vtk" / "case.pvd").getroot()
    return [(float(d.get("timestep")), int(d.get("part")), case / "vtk" / d.get("file")) for d in root.iter("DataSet")]


def part_reader(part_file):
    """ParaView's reader of a frame of the part: one .vtu, or the pieces of a .pvtu (rkpost --partitioned)."""
    if Path(part_file).suffix == ".pvtu":
        return XMLPartitionedUnstructuredGridReader(FileName=[str(part_file)])
    return XMLUnstructuredGridReader(FileName=[str(part_file)])


def time_text(t: float, end: float) -> str:
    """t in the unit that suits the whole run (us for an impact, ms for a forging stroke, s beyond)."""
    scale, unit = (1e6, "us") if end < 1e-3 else (1e3, "ms") if end < 1 else (1.0, "s")
    return f"t = {scale * t:.4g} {unit}"


def value_range(part_file, name):
    """The smallest and largest value of a point field in a frame (None where the frame has no such field)."""
    reader = part_reader(part_file)
    reader.UpdatePipeline()
    found = name in reader.PointData.keys()
    lo, hi = reader.PointData[name].GetRange() if found else (0.0, 0.0)
    Delete(reader)
    return (lo, hi) if found else None


def render(part_file, die_files, out, colour, title, size, top=None, ranks=0, low=0.0):
    """The part coloured by `colour`: a point field on [low, top] (the same scale for every frame), or
    the cells' rank as categories (ranks > 0: one colour and legend entry per rank). Returns the
    colour scale as drawn: {"scale": [low, high]} or {"categories": [legend entries]}."""
    view = CreateView("RenderView")
    view.ViewSize = size
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    try:  # ParaView 5.11: white background needs the palette override
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    part = part_reader(part_file)
    shown = Show(part, view)
    shown.Representation = "Surface With Edges" if colour[0] == "CELLS" else "Surface"
    shown.EdgeColor = [0.2, 0.2, 0.2]
    shown.Ambient, shown.Diffuse = 0.3, 0.8  # the faces turned from the headlight stay readable
    ColorBy(shown, colour)
    lut = GetColorTransferFunction(colour[1])
    if ranks:  # categorical: rank r is a colour of its own, named in the legend
        lut.InterpretValuesAsCategories = 1
        lut.AnnotationsInitialized = 1
        lut.Annotations = [v for r in range(ranks) for v in (str(r), f"rank {r}")]
        lut.ApplyPreset("Brewer Qualitative Set1" if ranks <= 9 else "Rainbow Uniform", True)
    else:  # a continuous field from low (a frame at rest draws low to the run's top, not 0 to 1e-38)
        lut.ApplyPreset("Turbo", True)
        lut.RescaleTransferFunction(low, max(top or 0.0, low + 1e-3))
        lut.AutomaticRescaleRangeMode = "Never"
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
    drawn = ({"categories": list(lut.Annotations[1::2])} if lut.InterpretValuesAsCategories
             else {"scale": [lut.RGBPoints[0], lut.RGBPoints[-4]]})  # RGBPoints: x, r, g, b per control point
    Delete(view)
    return drawn


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", type=Path)
    ap.add_argument("--frames", default="0,-1", help="frame positions in the .pvd (negative: from the end)")
    ap.add_argument("--size", default="900x700")
    a = ap.parse_args()
    size = [int(v) for v in a.size.split("x")]
    items = collection(a.case)
    times = sorted({t for t, part, _ in items})
    ranks = json.loads((a.case / "prep.json").read_text())["ranks"]
    chosen = sorted({int(v) % len(times) for v in a.frames.split(",")})
    first_part = {t: f for t, p, f in reversed(items) if p == 0}
    top = max(value_range(first_part[times[k]], "eq_plastic_strain")[1] for k in chosen)
    temperatures = [value_range(first_part[times[k]], "temperature") for k in chosen]
    hot = None if None in temperatures else (min(r[0] for r in temperatures), max(r[1] for r in temperatures))
    out = a.case / "plots"
    out.mkdir(exist_ok=True)
    made = []
    for k in chosen:
        t = times[k]
        part = [f for tt, p, f in items if tt == t and p == 0][0]
        dies = [f for tt, p, f in items if tt == t and p > 0]
        stem = part.stem.replace("frame_", "")
        drawn = render(part, dies, out / f"part_ep_{stem}.png", ("POINTS", "eq_plastic_strain"),
                       f"eq. plastic strain, {time_text(t, times[-1])}", size, top=top)
        made.append({"file": f"part_ep_{stem}.png", "field": "eq_plastic_strain", "time": t, **drawn})
        if hot:  # one scale for the frames, from the coolest to the hottest point
            drawn = render(part, dies, out / f"part_temperature_{stem}.png", ("POINTS", "temperature"),
                           f"temperature (K), {time_text(t, times[-1])}", size, top=hot[1], low=hot[0])
            made.append({"file": f"part_temperature_{stem}.png", "field": "temperature", "time": t, **drawn})
        drawn = render(part, [], out / f"part_rank_{stem}.png", ("CELLS", "rank"), "rank", size, ranks=ranks)
        made.append({"file": f"part_rank_{stem}.png", "field": "rank", "time": t, **drawn})
        print(f"pictures: {out}/part_ep_{stem}.png, {'part_temperature_' + stem + '.png, ' if hot else ''}"
              f"part_rank_{stem}.png (t = {t:g} s)")
    (out / "pictures.json").write_text(json.dumps({"pictures": made}, indent=1) + "\n")


main()
