"""Folds and laps found by rkpost (post/folds.hpp), and the part's contact with itself that holds them
(solver/contact/part_contact.hpp):
- a flat die closes the 2 mm slot of a C-shaped block (geometry/lap): the lap is reported once, in the
  slot, first at the frame where the die has travelled the slot's height less one spacing (where the
  finder's one-spacing reach meets the closing faces), with the particle field `fold` zero in every
  frame before and on the slot's faces after; the same on 1 and 2 ranks;
- the slot's two faces never pass through each other: their particles stay apart (the contact's spheres
  of 0.75 of their spacing), the pairs show in the history's part_contacts, and the energy balances;
- an upsetting to 50 % with friction (its bulge rolls onto the die) has none."""
import csv
import json
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
# The slot closes first at two places, near its root and at its open end (the upper arm bends), 3.9 mm
# apart, which join as it closes: one lap, reported where it first showed, at one frame (measured
# 2026-12-02: 2 and 18 particles at 1.2 ms)
rkcase.check(1 <= len(found) <= 2 and len({f[3] for f in found}) == 1 and all(3 <= f[0] <= 10 and 1 <= f[2] <= 3 for f in found),
             f"one lap reported, at one time, in the slot: {section.strip()}")
x, y, z, t, n = max(found, key=lambda f: f[4])
stroke = float(min(rows, key=lambda r: abs(float(r["time"]) - t))["die.stroke"])
# the finder flags the faces one spacing before they meet: at 1.0 mm of the die's travel. Measured
# 2026-12-02: first at the frame of 1.1 mm (the frames are 0.1 mm of travel apart; the arms themselves
# are squeezed a little), near the slot's root; the bound is that frame or the one before or after
rkcase.check(GAP - H - 0.05e-3 <= stroke <= GAP - H + 0.25e-3,
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

# The slot's faces (z = 4 and z = 2 mm at t = 0, x past the root at 3 mm): the closest pair of their
# particles over every frame. Measured 2026-12-02: 0.426 mm at the end, the contact's spheres of 0.75
# mm pressed 0.32 mm by the die's 30 kN; without the part's contact with itself (contact.self=false) the
# faces pass through each other, 0.05 mm and closing. The bound lies between the two.
X0 = frames[0][0]
upper = (abs(X0[:, 2] - 4e-3) < 1e-6) & (X0[:, 0] > 3e-3)
lower = (abs(X0[:, 2] - 2e-3) < 1e-6) & (X0[:, 0] > 3e-3)
closest = min(np.linalg.norm(x[upper][:, None, :] - x[lower][None, :, :], axis=2).min() for x, _ in frames)
pairs = max(float(r["part_contacts"]) for r in rows)
# the run's largest energy error past its start-up (solve.json; measured 2026-12-05 at the default CFL
# 0.9: 5.2e-3, up to 25 particles in contact; 2.7e-3 at CFL 0.5, in the same 7 605 mass-scaled steps:
# the density scaled less, each step a larger fraction of the material's limit)
worst = json.loads((cases[1] / "solve.json").read_text())["max_energy_error"]
rkcase.check(closest > 0.3e-3 and pairs > 0 and worst < 1.1e-2,
             f"the slot's faces stay apart: closest {1e3 * closest:.3f} mm, up to {pairs:.0f} particles in the part's "
             f"contact with itself, largest energy error {worst:.2e}")

# no fold where the free surface only rolls onto a die: upsetting to 50 % with friction
upset = tools.case("upset")
tools.prep(upset, 2, scene=rkcase.ROOT / "geometry" / "upsetting" / "scene_friction.yaml", sets=["discretization.spacing=2.5e-3"])
tools.solve(upset, 2)
tools.post(upset)
section, found = folds(upset)
rkcase.check(found == [] and "None found." in section, f"upsetting to 50 %: {section.strip()}")
