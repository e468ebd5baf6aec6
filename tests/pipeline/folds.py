"""Folds and laps found by rkpost (post/folds.hpp):
- a flat die closes the 2 mm slot of a C-shaped block (geometry/lap): the lap is reported once, in the
  slot, first at the frame where the die has travelled the slot's height less half a spacing (where the
  finder's half-spacing reach meets the closing faces), with the particle field `fold` zero in every
  frame before and on the slot's faces after; the same on 1 and 2 ranks;
- an upsetting to 50 % with friction (its bulge rolls onto the die) has none."""
import csv
import re

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
LAP = rkcase.ROOT / "geometry" / "lap" / "scene.yaml"
H, GAP = 1e-3, 2e-3  # the spacing and the slot's height (m)


def folds(case):
    report = (case / "report.md").read_text()
    section = report.split("## Folds and laps")[1].split("\n## ")[0]
    found = re.findall(r"a fold at \(([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+)\) mm from t = ([0-9.e+-]+) s \((\d+) surface", section)
    return section, [(float(x), float(y), float(z), float(t), int(n)) for x, y, z, t, n in found]


def flags(case):
    out = []
    for f in sorted((case / "vtk").glob("frame_*.vtu")):
        m = meshio.read(f)
        out.append((m.points, m.point_data["fold"].ravel()))
    return out


cases = {}
for ranks in (1, 2):
    case = tools.case(f"lap_{ranks}")
    tools.prep(case, ranks, scene=LAP)
    tools.solve(case, ranks)
    tools.post(case)
    cases[ranks] = case
section, found = folds(cases[1])
rows = list(csv.DictReader(open(cases[1] / "history.csv")))
rkcase.check(len(found) == 1, f"one lap reported: {section.strip()}")
x, y, z, t, n = found[0]
stroke = float(min(rows, key=lambda r: abs(float(r["time"]) - t))["die.stroke"])
# the finder flags the faces half a spacing before they meet: at 1.5 mm of the die's travel. Measured
# 2026-12-02: first at the frame of 1.6 mm (the frames are 0.1 mm of travel apart; the arms themselves
# are squeezed a little), at the slot's open end; the bound is that frame or the one before or after
rkcase.check(GAP - 0.5 * H - 0.05e-3 <= stroke <= GAP - 0.5 * H + 0.25e-3 and 3 <= x <= 10 and 1 <= z <= 3,
             f"the lap in the slot at ({x}, {y}, {z}) mm, first at t = {t} s with the die at {1e3 * stroke:.3f} mm "
             f"({n} particles)")
frames = flags(cases[1])
times = [float(v) for v in re.findall(r'timestep="([^"]+)" part="0"', (cases[1] / "vtk" / "case.pvd").read_text())]
before = [k for k, s in enumerate(times) if s < t * (1 - 1e-9)]
last_points, last_flags = frames[-1]
on = last_points[last_flags == 1]
rkcase.check(all(not f.any() for _, f in (frames[k] for k in before)) and len(on) > 0
             and (on[:, 0] >= 3e-3 - H).all() and (on[:, 2] > 0.5e-3).all() and (on[:, 2] < 3.5e-3).all(),
             f"the field `fold`: none in the {len(before)} frames before, {len(on)} particles on the slot's faces at the end")
rkcase.check(folds(cases[2])[1] == found, "the same lap on 2 ranks")

# no fold where the free surface only rolls onto a die: upsetting to 50 % with friction
upset = tools.case("upset")
tools.prep(upset, 2, scene=rkcase.ROOT / "geometry" / "upsetting" / "scene_friction.yaml", sets=["discretization.spacing=2.5e-3"])
tools.solve(upset, 2)
tools.post(upset)
section, found = folds(upset)
rkcase.check(found == [] and "None found." in section, f"upsetting to 50 %: {section.strip()}")
