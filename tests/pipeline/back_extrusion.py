"""Back extrusion (section 5.2 of Wang et al. 2007) as the scene stands, with its reference updates, through its
full 15 mm stroke on 2 ranks, against the scene's checks: energy identity within 2 %, the volume kept
(below), the punch force curve against the measured one (below), and a cup wall as high as the
volume it holds.
Measured 2026-12-01: 1.12 % at most, the wall's top (98th percentile of its
particles) 28.45 mm above the punch face where volume constancy puts it at 29.4 mm (97 %).
With the dies holding the particles' coefficients instead of the material at them (u^h(X_I)), and
each update putting the material that the penalty let into a die back onto its surface, the wall
reached 25.9 mm (88 %): every update cut the spring's layer off (12 mm^3 of 9 400). Before the dies
held the integration points it reached 21.6 mm (73 %), and the updates carried points deep into the
dies: left there, the run ended at 3.5 % and +1.8 %; with the supports' growth measured by the
scale-dependent pivot ratio as well, 1 625 of the 1 651 supports grew 6x at 5.5 mm, the punch lost
312 of its 341 contacts within 50 steps and its force fell from 700 kN to 3-70 kN."""
import csv
import json
import subprocess
import sys

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
case = tools.case("back_extrusion")
tools.prep(case, 2, scene=rkcase.ROOT / "geometry" / "back_extrusion" / "scene.yaml")
tools.solve(case, 2, sets=["time.output_interval=0.15e-3"])
solve = json.loads((case / "solve.json").read_text())
with open(case / "history.csv") as f:
    rows = list(csv.DictReader(f))
stroke = float(rows[-1]["punch.stroke"])
rkcase.check(abs(stroke - 15e-3) < 1e-6, f"full stroke: {1e3 * stroke:.3f} mm, {solve['reference_updates']} reference updates")
# The punch force (full part), mean over +-1 mm of stroke (67 history rows), measured at the scene's
# 2.5 mm spacing and at 1.6 mm (both on 1 rank):
#   stroke (mm)    2      5      8      11     14
#   2.5 mm (kN)    878.9  960.8  1070.9 1079.0 1127.6
#   1.6 mm (kN)    869.0  970.3  1023.5 1035.2 1053.1   (2.5 mm is +1.1, -1.0, +4.6, +4.2, +7.1 % off it)
# and the 1.25 mm resolution within 0.1-2.1 % of the 1.6 mm one. Each window's tolerance is twice
# the spread of the test's resolution against the finer one there, and no less than twice the
# 2.1 % that the finer resolutions still move it: 4.2, 4.2, 9.3, 8.5, 14.1 %. A change of the
# contact, the friction or the reference updates that moves the force by more than a resolution
# step fails here; the force collapse of the supports' growth (700 kN to 3-70 kN) by far.
FORCE_KN = {2: (878.9, 869.0), 5: (960.8, 970.3), 8: (1070.9, 1023.5), 11: (1079.0, 1035.2), 14: (1127.6, 1053.1)}
for s_mm, (measured, finer) in FORCE_KN.items():
    near = [float(r["punch.force"]) for r in rows if abs(float(r["punch.stroke"]) - 1e-3 * s_mm) <= 1e-3]
    force = sum(near) / max(len(near), 1) / 1e3
    tol = max(2 * abs(measured / finer - 1), 2 * 0.021)
    rkcase.check(len(near) >= 60 and abs(force / measured - 1) <= tol,
                 f"punch force {force:.1f} kN (full part) at {s_mm} +- 1 mm of stroke: the measured {measured} kN "
                 f"within {100 * tol:.1f} % (1.6 mm: {finer} kN)")
# After each reference update the step grows to twice the cells' estimate on the new reference's edges
# (reference_updates.step_growth; at most their estimate on the t = 0 edges), the contact's stiffness
# kept to that estimate and its springs, held at the longer step's limit, damped (contact.damping).
# Measured 2026-12-05 on 1 rank: 11 824 steps, punch work 3887.6 J; with step_growth 1 (the step on
# the new reference's edges) 22 383 steps and 3901.7 J, and 3901.0 J before the growth was built (the
# round-off's spread, 0.02 %). The work is held within twice its measured shift (0.34 %) of the
# short step's; a step that no longer grows takes 1.9x the steps (bounded at 1.1x the measured).
work = float(rows[-1]["punch.work"])
rkcase.check(abs(work / 3901.0 - 1) < 0.007, f"punch work {work:.1f} J, the short step's 3901.0 J within 0.7 %")
rkcase.check(solve["steps"] < 13000, f"{solve['steps']} steps (11 824 measured; 22 383 at step_growth 1)")
held = [int(float(r["contacts"])) + int(float(r["point_contacts"])) for r in rows if float(r["punch.stroke"]) > 2e-3]
contacts = np.percentile(held, 10)
rkcase.check(contacts >= 250, f"{contacts:.0f} particles and points in contact in 90 % of the rows after 2 mm of stroke")
error = max(abs(float(r["energy_error"])) for r in rows[len(rows) // 10:])
rkcase.check(error < 0.02, f"energy error {100 * error:.2f} % at most after the first 10 % of the run")
# The points' volume (sum w_g J) is elastic by construction (the return map keeps det F_p = 1): here
# the compression under the mean pressure, 0.43 % at the end (554 MPa / K). What the discretization
# loses shows in the cells through the particles' material positions, less the points' change
# (scripts/forming_report.py; a hex cell's 6 tetrahedra read the twisted cells at the punch corner).
# Measured 2026-12-05 with Coulomb friction's elastic stick: 1.68 % at most, in the last 0.3 ms, where
# the cup wall, held at the punch and the container, shears across two or three particles. The stick
# that stopped the sliding one step at a time let the material creep along the tools and read 0.72 %
# at the default step, but 1.35 % at CFL 0.15: the growth is the friction's, converged in the step.
# The bound is about twice that; the cup wall shortfall of the coefficient-held contact (12 % of its
# height) was some 6 % of the volume.
volume = max(abs(float(r["volume_change"])) for r in rows)
rkcase.check(volume < 0.01, f"volume change of the points {100 * volume:.2f} % at most (elastic)")

# The cup wall (particles beyond the punch radius 14 mm, inside the container's 20 mm) holds the
# material of that annulus above the punch face's level plus all the punch displaced: by volume
# constancy it stands s + s 14^2 / (20^2 - 14^2) above the face after a stroke s (29.41 mm).
tools.post(case)
report = json.loads(subprocess.run([sys.executable, str(rkcase.ROOT / "scripts" / "forming_report.py"), str(case), "--json"],
                                   check=True, capture_output=True, text=True).stdout)
lost = report["max_abs_cells_less_points"]
rkcase.check(lost < 0.034, f"cells through the particles within {100 * lost:.2f} % of the points' volume at every frame")
x = meshio.read(sorted((case / "vtk").glob("frame_*.vtu"))[-1]).points * 1e3
face = 30 - 1e3 * stroke
wall = x[np.hypot(x[:, 0], x[:, 1]) > 14.5, 2]
height = np.percentile(wall, 98) - face
expected = (30 - face) * 14**2 / (20**2 - 14**2) + (30 - face)
rkcase.check(height > 0.94 * expected,
             f"cup wall {height:.2f} mm above the punch face, {100 * height / expected:.0f} % of the {expected:.2f} mm volume constancy gives")
