"""An upset then a closed-die stage (geometry/upsetting/scene_closed_die.yaml), 2.5 mm spacing, 2 ranks:
the upsetting scene to 2.2 ms (21 % reduction), then a stage in which the same die goes on down while a
ring die at rest (inner radius 12 mm, to 3 mm above the mid-plane) stops the bulge. Frictionless, the
billet stays a cylinder of radius R0 sqrt(H0 / H) until it meets the ring: at the stroke
s* = H0 (1 - (R0 / 12 mm)^2) = 3.056 mm. Measured 2026-12-03: at the stage's start (2.1 mm) the die's
force 3.6 % below free upsetting's closed form sigma(ln H0/H) pi R0^2 H0/H; the ring first loaded at
3.076 mm; the die's force at 4.1 mm 527 kN, 2.13x the closed form there (247 kN); the chain's largest
energy error 2.8e-5."""
import csv
import json
import math

import rkcase

tools = rkcase.tools_from_argv()
GEO = rkcase.ROOT / "geometry" / "upsetting"
SPACING = "discretization.spacing=2.5e-3"
R0, H0, RING = 10e-3, 10e-3, 12e-3                     # the billet's radius and half-height, the ring's radius
K, EPS0, N = 576.79e6, 0.01658, 0.3593                 # the scene's power law

upset = tools.case("upset")
tools.prep(upset, 2, scene=GEO / "scene.yaml", sets=[SPACING])
tools.solve(upset, 2, sets=["time.end=2.2e-3"])
closed = tools.case("closed")
tools.prep(closed, 2, scene=GEO / "scene_closed_die.yaml", sets=[SPACING])
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", closed, "--quiet", "--from", upset])
rows = list(csv.DictReader(open(closed / "history.csv")))
solve = json.loads((closed / "solve.json").read_text())

# the energy balance over the chain (the issue of a closed die: the material trapped, the step falling)
rkcase.check(solve["max_energy_error"] < 1e-4, f"the closed-die stage completes: largest energy error "
             f"{solve['max_energy_error']:.2e} (measured 2.8e-5)")

# the ring takes load where the free cylinder's radius reaches it (the contact acts within a fraction of
# a spacing: measured +0.02 mm)
s_star = H0 * (1 - (R0 / RING) ** 2)
loaded = [r for r in rows if abs(float(r["ring.force"])) > 0]
rkcase.check(bool(loaded) and abs(float(loaded[0]["die.stroke"]) - s_star) < 0.05e-3,
             f"the ring first loaded at a stroke of {1e3 * float(loaded[0]['die.stroke']):.3f} mm "
             f"(the free cylinder reaches it at {1e3 * s_star:.3f} mm)" if loaded else "the ring is never loaded")
rkcase.check(all(float(r["ring.force"]) == 0 for r in rows if float(r["die.stroke"]) < s_star - 0.2e-3),
             "no load on the ring before the bulge reaches it")



def free_force(s):
    """Homogeneous frictionless upsetting at stroke s: the flow stress at ln(H0 / H) over the area."""
    H = H0 - s
    return K * (EPS0 + math.log(H0 / H)) ** N * math.pi * R0 ** 2 * H0 / H


# free at the stage's start (the upsetting test measures this closely; here the base of the ratio below)
first = rows[0]
start = float(first["die.force"]) / free_force(float(first["die.stroke"])) - 1
rkcase.check(abs(start) < 0.07, f"free at the start, {1e3 * float(first['die.stroke']):.2f} mm: the die's force "
             f"{100 * start:+.1f} % from the closed form (measured -3.6 %)")

# confined, the die needs far more than free upsetting's closed form at the same stroke
last = rows[-1]
s = float(last["die.stroke"])
free = free_force(s)
ratio = float(last["die.force"]) / free
rkcase.check(ratio > 1.8, f"at {1e3 * s:.2f} mm the die pushes {float(last['die.force']) / 1e3:.0f} kN, {ratio:.2f}x free "
             f"upsetting's {free / 1e3:.0f} kN (measured 2.13x)")
