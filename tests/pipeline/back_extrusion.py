"""Back extrusion (BENCHMARKS.md case 4) as the scene stands, with its reference updates, through its
full 15 mm stroke on 2 ranks, against the scene's checks: energy identity within 2 %, volume change
below 0.5 %, a punch force with no collapse. Measured 2026-11-23: 1.54 % and 0.34 % at most, 0.64 to
0.91 MN. Before the integration points were kept out of the dies at an update, the same run ended at
3.5 % and +1.8 % (points left inside strained against nothing), and with the supports' growth
measured by the scale-dependent pivot ratio as well, 1 625 of the 1 651 supports grew 6x at 5.5 mm,
the punch lost 312 of its 341 contacts within 50 steps and its force fell from 700 kN to 3-70 kN.
What this run does not check: the particle cloud ends ~12 % short of volume (README)."""
import csv
import json

import rkcase

tools = rkcase.tools_from_argv()
case = tools.case("back_extrusion")
tools.prep(case, 2, scene=rkcase.ROOT / "geometry" / "back_extrusion" / "scene.yaml")
tools.solve(case, 2, sets=["time.output_interval=1.5e-3"])
solve = json.loads((case / "solve.json").read_text())
with open(case / "history.csv") as f:
    rows = list(csv.DictReader(f))
stroke = float(rows[-1]["punch.stroke"])
rkcase.check(abs(stroke - 15e-3) < 1e-6, f"full stroke: {1e3 * stroke:.3f} mm, {solve['reference_updates']} reference updates")
for s0 in (2e-3, 5.75e-3, 8e-3, 11e-3, 14e-3):
    near = [float(r["punch.force"]) for r in rows if abs(float(r["punch.stroke"]) - s0) <= 0.3e-3]
    force = sum(near) / max(len(near), 1)
    rkcase.check(len(near) >= 10 and 0.55e6 < force < 1.1e6, f"punch force {force / 1e3:.0f} kN (full part) at {1e3 * s0:.2f} mm")
contacts = min(int(float(r["contacts"])) for r in rows if float(r["punch.stroke"]) > 2e-3)
rkcase.check(contacts >= 250, f"at least {contacts} particles in contact after 2 mm of stroke")
error = max(abs(float(r["energy_error"])) for r in rows[len(rows) // 10:])
rkcase.check(error < 0.02, f"energy error {100 * error:.2f} % at most after the first 10 % of the run")
volume = max(abs(float(r["volume_change"])) for r in rows)
rkcase.check(volume < 0.005, f"volume change {100 * volume:.2f} % at most")
