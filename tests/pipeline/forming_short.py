"""Short runs of the two forming scenes of Wang et al. 2007 (sections 5.2 and 5.3) at a coarse spacing:
back extrusion on 2 ranks bitwise equal to 1 rank (die contact with friction across the partition,
through reference updates), and stopped half-way and restarted bitwise equal to the whole run (the
dies' and the symmetry planes' contact work in the checkpoint);
the wheel-forging sector keeps its cut faces on their non-axis-aligned symmetry planes (exact EBCs), conserves
volume and energy, presses with the measured punch force at the end of its 0.3 mm stroke, presses as deep
with the same work at the default CFL 0.9 as at 0.5 (the contact's stiffness does not follow the CFL), and
forming_report.py writes its numbers and pictures; and a die whose curve ends at the run's end reads its
last row's force as the rows before it (the contact's dashpots meet the die's velocity over the step the
part took, not the stopped die's)."""
import csv
import json
import subprocess

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
geometry = rkcase.ROOT / "geometry"

# Back extrusion: 1 rank against 2 ranks, bitwise.
# the punch strikes at 10 m/s: at this coarse spacing the impact's start-up energy error passes 5 %;
# reference updates every 2 % of strain (the scene's 20 % comes later) put a few in these 0.6 mm
short = ["time.output_interval=30e-6", "health.max_energy_error=0.2", "reference_updates.strain=0.02"]
frames = {}
for ranks in (1, 2):
    c = tools.case(f"back_extrusion_r{ranks}")
    tools.prep(c, ranks, scene=geometry / "back_extrusion" / "scene.yaml", sets=["discretization.spacing=4e-3"])
    tools.solve(c, ranks, sets=short + ["time.end=60e-6"])
    tools.post(c)
    m = meshio.read(c / "vtk" / "frame_00002.vtu")
    order = np.argsort(m.point_data["global_id"].ravel())
    frames[ranks] = (m.points[order], m.point_data["velocity"][order], m.point_data["eq_plastic_strain"][order])
rkcase.check(frames[1][2].max() > 0, f"back extrusion: the punch deforms the billet (max ep {frames[1][2].max():.3f})")
updates = json.loads((tools.work / "back_extrusion_r1" / "solve.json").read_text())["reference_updates"]
rkcase.check(updates >= 2, f"back extrusion: {updates} reference updates in 0.6 mm of stroke")
rkcase.check(all(np.array_equal(a, b) for a, b in zip(frames[1], frames[2])),
             "back extrusion with friction and reference updates: 2 ranks bitwise equal to 1 rank")
# The same 2-rank run stopped at 0.3 mm (an output time, as in the whole run) and restarted.
split = tools.case("back_extrusion_split")
tools.prep(split, 2, scene=geometry / "back_extrusion" / "scene.yaml", sets=["discretization.spacing=4e-3"])
tools.solve(split, 2, sets=short + ["time.end=30e-6"])
mid = json.loads((split / "solve.json").read_text())["reference_updates"]
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", split, "--quiet", "--restart"] +
          sum([["--set", s] for s in short + ["time.end=60e-6"]], []))
tools.post(split)
m = meshio.read(split / "vtk" / "frame_00002.vtu")
order = np.argsort(m.point_data["global_id"].ravel())
resumed = (m.points[order], m.point_data["velocity"][order], m.point_data["eq_plastic_strain"][order])
whole = (tools.work / "back_extrusion_r2" / "history.csv").read_text().splitlines()
again = (split / "history.csv").read_text().splitlines()
rkcase.check(mid >= 1 and all(np.array_equal(a, b) for a, b in zip(frames[2], resumed)) and whole[-1] == again[-1],
             f"back extrusion stopped after {mid} reference update{'s' * (mid != 1)} and restarted: the last frame and history row "
             "bitwise equal to the whole run")
# Coulomb friction's elastic stick holds at any step: no warning at the default CFL 0.9.
p = tools.solve(tools.work / "back_extrusion_r1", 1, sets=short + ["time.end=1e-6"])
rkcase.check("warning: time.cfl" not in p.stderr, "back extrusion (Coulomb friction) at the default CFL 0.9: no warning")

# Wheel forging sector: 0.3 mm of stroke, exact symmetry planes (the nodal ones let the material at the
# cut faces drift off them by ~3 % of its motion, measured in essential_bcs.py), total Lagrangian (the exact
# method's rows are not rebuilt at reference updates; 0.3 mm strains far less than an update's 0.2).
c = tools.case("wheel_forging")
tools.prep(c, 2, scene=geometry / "wheel_forging" / "scene.yaml",
           sets=["discretization.spacing=4e-3", "discretization.ebc_method=transformation", "reference_updates.strain=0"])
p = tools.solve(c, 2, sets=["time.end=30e-6", "time.output_interval=10e-6"])
rkcase.check("warning: time.cfl" not in p.stderr, "wheel (frictionless) at the default CFL 0.9: no warning")
tools.post(c)
first = meshio.read(c / "vtk" / "frame_00000.vtu")
last = meshio.read(c / "vtk" / "frame_00003.vtu")
order0 = np.argsort(first.point_data["global_id"].ravel())
order1 = np.argsort(last.point_data["global_id"].ravel())
x0, x1 = first.points[order0], last.points[order1]
for angle in (30, 60):
    n = np.array([-np.sin(np.radians(angle)), np.cos(np.radians(angle)), 0.0])
    on = np.abs(x0 @ n) < 1e-9
    off = np.abs(x1[on] @ n).max()
    moved = np.linalg.norm(x1[on] - x0[on], axis=1).max()
    rkcase.check(on.sum() > 10 and moved > 1e-5 and off < 1e-12,
                 f"wheel sector: the {on.sum()} particles of the {angle}-degree cut face moved up to "
                 f"{1e3 * moved:.3f} mm and stayed on its plane within {off:.1e} m")
# the punch face (15 < r < 40 mm) is at z = 40 mm - stroke: no particle may sit above it
r1 = np.hypot(x1[:, 0], x1[:, 1])
under = (r1 > 15.5e-3) & (r1 < 39.5e-3)
top = x1[under, 2].max()
rkcase.check(top < 39.7e-3 + 1e-5, f"wheel: no particle inside the punch (highest under its face: z = {1e3 * top:.4f} mm, "
             f"face at 39.7 mm)")
report = subprocess.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / "forming_report.py", c, "--json"],
                        capture_output=True, text=True, check=True)
res = json.loads(report.stdout)
print(json.dumps(res, indent=2))
rkcase.check(res["max_penetration_mm"] < 0.01, f"deepest penetration {res['max_penetration_mm']:.4f} mm < 0.01 mm")
rkcase.check(abs(res["dies"]["punch"]["stroke_mm"] - 0.3) < 1e-9, "punch stroke 0.3 mm at 30 us (10 m/s)")
# The punch force (full part) at the end of the stroke, as the mean over its last 0.05 mm (34 history
# rows at the default CFL 0.9, 57 at 0.5: a row per step at most; the penalty contact rings, the last
# row alone moved from 285 to 469 kN between runs). Measured at CFL 0.5: 355.9 kN (the same, bitwise,
# on 1 rank); 359.0 kN at CFL 0.4, 355.2 kN at penalty scale 0.2, 332.6 and 340.0 kN at spacing 3.6 and
# 4.4 mm: at most 6.5 % from it, the tolerance 13 % is twice that. At the default 0.9: 355.3 kN
# (2026-12-05).
with open(c / "history.csv") as f:
    near = [float(r["punch.force"]) for r in csv.DictReader(f) if 0.25e-3 <= float(r["punch.stroke"]) <= 0.3e-3 + 1e-12]
force = sum(near) / max(len(near), 1) / 1e3
rkcase.check(len(near) >= 30 and abs(force / 355.9 - 1) < 0.13,
             f"punch force {force:.1f} kN (full part) over the stroke's last 0.05 mm ({len(near)} rows): the measured "
             "355.9 kN within 13 %")
rkcase.check(res["max_abs_volume_change"] < 0.005, f"volume change {100 * res['max_abs_volume_change']:.3f} % < 0.5 %")
# (the punch's impact at 10 m/s makes the start-up error larger; the full runs are checked by the studies)
rkcase.check(res["final_energy_error"] < 0.02, f"energy identity within {100 * res['final_energy_error']:.2f} % at "
             f"the end (< 2 %; {100 * res['max_energy_error']:.2f} % at most during the impact)")

# A CFL changes the step, not the contact's stiffness (docs/decisions.md, "Contact laws"): the same 0.3 mm at
# the default 0.9 takes 1.8x fewer steps than at 0.5 and presses as deep.
slow = tools.case("wheel_forging_cfl")
tools.prep(slow, 2, scene=geometry / "wheel_forging" / "scene.yaml",
           sets=["discretization.spacing=4e-3", "discretization.ebc_method=transformation", "reference_updates.strain=0"])
tools.solve(slow, 2, sets=["time.end=30e-6", "time.output_interval=10e-6", "time.cfl=0.5"])


def pressed(case):
    with open(case / "history.csv") as f:
        rows = list(csv.DictReader(f))
    steps = json.loads((case / "solve.json").read_text())["steps"]
    return steps, max(float(r["max_penetration"]) for r in rows), float(rows[-1]["punch.work"])


(n5, d5, w5), (n9, d9, w9) = pressed(slow), pressed(c)
# Measured: 356 and 198 steps, the deepest penetration +4.1 %, the punch's work -0.024 % (with the scale not
# following the CFL, the contact 3.2x softer: +76 % and -0.79 %); the tolerances twice those.
rkcase.check(n5 / n9 > 1.7 and abs(d9 / d5 - 1) < 0.082 and abs(w9 / w5 - 1) < 5e-4,
             f"wheel at the default CFL 0.9: {n9} steps against {n5}, the deepest penetration {100 * (d9 / d5 - 1):+.1f} % "
             f"(< 8.2 %) and the punch's work {100 * (w9 / w5 - 1):+.3f} % (< 0.05 %) from CFL 0.5's")
for png in ("force_stroke.png", "energies.png", "stages.png"):
    size = (c / "plots" / png).stat().st_size
    rkcase.check(size > 10_000, f"plots/{png} written ({size} bytes)")

# The upsetting's die on a curve that ends at time.end, at CFL 1.5 (the penalty springs held at their step's
# limit, with their dashpots): the last row's force follows the rows before it. Measured 2026-12-08 (2.5 mm,
# 1 rank): 65 364.7 then 65 372.4 N; with the die's velocity taken after t (the stopped die's) 62 773.7 N,
# -4.0 %, and -8.7 % on the hot upsetting's full stroke at 2.5 mm (51.3 against 56.2 kN)
ended = tools.case("upsetting_curve_end")
tools.prep(ended, 1, scene=geometry / "upsetting" / "scene.yaml", sets=["discretization.spacing=2.5e-3"])
tools.solve(ended, 1, sets=["time.end=0.5e-3", "dies[0].motion.curve=[[0,0],[0.2e-3,0.1e-3],[0.5e-3,0.4e-3]]", "time.cfl=1.5"])
rows = list(csv.DictReader(open(ended / "history.csv")))
force = [float(r["die.force"]) for r in rows[-3:]]
# the rows before the end rise by 30-50 N a row; 0.5 % is ten times that and an eighth of the old drop
rkcase.check(abs(force[-1] / force[-2] - 1) < 0.005, f"the die's force at the curve's end, {force[-1]:.1f} N, follows the rows "
             f"before it, {force[0]:.1f} and {force[1]:.1f} N")
