"""The upsetting benchmark with its billet from CAD (geometry/upsetting_step: the one eighth of the
cylinder as STEP, meshed in hexahedra split from tetrahedra) against the closed form F = sigma(ep)
A0 H0 / H, at 2 mm spacing (757 particles), quasi-static. Measured 2026-12-02: force errors -2.73,
-2.94, -1.73, -2.09, -1.60 % at 10-50 % reduction (the .geo billet's structured O-grid at the same
spacing: -0.66 to -1.01 %; the STEP billet at 1.5 mm: -0.85 to -1.29 %, converging); diameter
+0.89 %; volume 0.37 % below the cylinder's (the facets of the curved face); kinetic/internal 0.66 %."""
import csv
import json
import re
import math

import rkcase
from upsetting_check import check

tools = rkcase.tools_from_argv()
case = tools.case("upsetting_step")
tools.prep(case, 1, scene=rkcase.ROOT / "geometry" / "upsetting_step" / "scene.yaml", sets=["discretization.spacing=2e-3"])
prep = json.loads((case / "prep.json").read_text())
cylinder = math.pi * 0.01 ** 2 / 4 * 0.01  # one eighth of D0 = H0 = 20 mm
rkcase.check(abs(prep["volume_m3"] / cylinder - 1) < 0.006,
             f"the STEP billet's volume {prep['volume_m3']:.5g} m^3, {100 * (prep['volume_m3'] / cylinder - 1):+.2f} % "
             "from the cylinder's (the curved face's facets: -0.37 % measured)")
rkcase.check(0.5 < prep["spacing_achieved_m"] / 2e-3 < 1.5, f"spacing achieved {1e3 * prep['spacing_achieved_m']:.2f} mm")
tools.solve(case, 1, sets=["time.mass_scaling_dt=3e-7", "time.output_interval=1e-3"])
tools.post(case)
res = check(case)
for f in res["force"]:
    # 2.94 % the largest measured; 4 % holds it with the spread of another platform's gmsh mesh
    rkcase.check(abs(f["error"]) < 0.04, f"{100 * f['reduction']:.0f} % reduction: force {f['force_kN']:.1f} kN, "
                 f"exact {f['exact_kN']:.1f} kN ({100 * f['error']:+.2f} %, tolerance 4 %)")
rkcase.check(len(res["force"]) == 5, "reached 50 % reduction")
rkcase.check(abs(res["diameter_error"]) < 0.02, f"diameter {res['diameter_mm']:.2f} mm ({100 * res['diameter_error']:+.2f} %)")
rkcase.check(res["max_kinetic_internal_ratio"] < 0.01, f"quasi-static: KE/IE <= {100 * res['max_kinetic_internal_ratio']:.2f} %")

# rkpost with its plots: the force against stroke, and the report's press section (the largest force
# is the 50 % one, at the end of the stroke, 5 mm of the modeled half); the ParaView renders are
# rkpost_paraview's (1.4 s against 9.2 s with them, 2026-12-07)
p = tools.run([tools.bin / "rkpost", case, "--quiet", "--plots-only"])
rkcase.check(not list((case / "plots").glob("part_*.png")), "--plots-only: no ParaView pictures")
report = (case / "report.md").read_text()
rkcase.check((case / "plots" / "force_stroke.png").exists() and "## Press force" in report
             and "![force against stroke](plots/force_stroke.png)" in report and "| die | " in report,
             "report.md: the press section and the force-stroke plot")
# the press sized by the force's running mean over 2 % of the rows (as the plot draws it), the largest
# single row beside it: recomputed here from history.csv
force = [float(r["die.force"]) for r in csv.DictReader(open(case / "history.csv"))]
k = max(1, len(force) // 50)
means = [sum(force[i - k + 1:i + 1]) / k for i in range(k - 1, len(force))]
said = re.search(r"\| die \| (\S+) kN \| \S+ mm \| (\S+) kN \| \S+ mm \|", report)
rkcase.check(said is not None and abs(float(said[1]) / (1e-3 * max(means, key=abs)) - 1) < 1e-3
             and abs(float(said[2]) / (1e-3 * max(force, key=abs)) - 1) < 1e-3,
             f"report.md's press force: the running mean's peak {said and said[1]} kN "
             f"({1e-3 * max(means, key=abs):.4g}), the largest row {said and said[2]} kN ({1e-3 * max(force, key=abs):.4g})")
