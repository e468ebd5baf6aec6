"""Heat conduction alone, in the steel bar of geometry/heat_slab (20 x 4 x 4 mm at 1 mm spacing), against
the exact solutions that scripts/heat_slab_check.py computes (Carslaw & Jaeger 1959):
- both ends held at 400 K, the bar at 300 K (scene.yaml): the particles' T^h within 1 % of the series
  at 2, 4, 6, 8 and 10 s; and the same answer whatever the thermal update's interval: one update every
  mechanical step against the default (every ~3 steps, as the stable step allows);
- the bar on a die at 300 K (scene_die.yaml, copper at 600 K, 2000 W/m^2 K): the series of the
  film-cooled slab, and the lumped capacity T = Td + (T0 - Td) exp(-h A t / (rho c V)) for the mean;
  the heat the die took equals the heat the bar lost;
- every face cooled by a 5000 W/m^2 K film (scene_convection.yaml): the product of three slab series;
- the bar with its far half starting at 400 K (scene_regions.yaml, a temperature region), every face
  insulated: the cosine series of the step, and a heat content that stays what it was;
- the ends held at 300 and 400 K with k(T) rising from 200 to 600 W/m K (scene_conductivity.yaml): the
  steady profile of the Kirchhoff transform, bent toward the cold end (362 K at the middle);
- a black body at 1000 K radiating to 300 K (scene_radiation.yaml, copper: nearly uniform): the lumped
  Stefan-Boltzmann cooling in closed form."""
import csv
import json
import subprocess
import sys

import rkcase

tools = rkcase.tools_from_argv()
folder = rkcase.ROOT / "geometry" / "heat_slab"


def run(name, scene, sets=()):
    case = tools.case(name)
    tools.prep(case, 1, scene=folder / scene)
    tools.solve(case, 1, sets=sets)
    tools.post(case)
    out = subprocess.run([sys.executable, rkcase.ROOT / "scripts" / "heat_slab_check.py", case, "--json"],
                         capture_output=True, text=True, check=True).stdout
    return case, json.loads(out)


# Measured 2026-12-02: largest error 0.75 % (at 2 s, the start's jump at the ends; 1.28 % at 2 mm
# spacing, 0.39 % at 0.5 mm), 0.10 % at 10 s. The bound, 1 %, is above it.
case, fixed = run("slab", "scene.yaml")
rkcase.check(fixed["max_error"] < 0.01, f"held ends: T^h within {fixed['max_error']:.4f} of the series (< 0.01)")
every, fixed1 = run("slab_every_step", "scene.yaml", ["thermal.max_steps_per_update=1", "time.end=4"])
means = [f["mean_K"] for f in fixed["frames"][:2]], [f["mean_K"] for f in fixed1["frames"][:2]]
gap = max(abs(a - b) for a, b in zip(*means)) / 100
# measured 3.4e-4 of the 100 K step in the means at 2 and 4 s (2026-12-07): the explicit step's error,
# a twentieth of the discretization's (1.7e-4 with the looser bound below, whose step was shorter by sqrt(3))
rkcase.check(gap < 7e-4, f"an update every step and every few steps agree within {gap:.1e} of T1 - T0 (< 7e-4)")
summary = [json.loads((c / "solve.json").read_text()) for c in (case, every)]
per_step = [r["thermal_updates"] / r["steps"] for r in summary]  # measured 0.20 (every 5 steps of 2 ms) and 1.0
rkcase.check(per_step[0] < 0.3 and per_step[1] > 0.99, f"thermal updates per mechanical step: {per_step[0]:.2f} by default, {per_step[1]:.2f} capped at 1")
# The thermal step, Gershgorin's bound on the conduction over the capacities, bounds each point's
# conductivity k J C^-1 by its largest row sum (k in the bar at rest): measured 11.78 ms; with its
# Frobenius norm (sqrt(3) k), the bound before, 6.80 ms
step = summary[0]["thermal_step_s"]
rkcase.check(step > 0.011, f"the thermal stable step {1e3 * step:.2f} ms (> 11 ms; 6.80 ms with the Frobenius norm's bound)")

# Measured: series 0.06 %, lumped 0.23 % (the lumped model's own error at Biot 0.02 is of that size)
case, die = run("slab_die", "scene_die.yaml")
rkcase.check(die["max_error"] < 0.002, f"die chilling: T^h within {die['max_error']:.4f} of the film-cooled slab's series (< 0.002)")
rkcase.check(die["max_lumped_error"] < 0.005, f"die chilling: the mean within {die['max_lumped_error']:.4f} of the lumped capacity (< 0.005)")
rows = list(csv.DictReader(open(case / "history.csv")))
V = json.loads((case / "prep.json").read_text())["volume_m3"]
lost = 8900 * 385 * V * (600 - float(rows[-1]["temperature_mean"]))
taken = float(rows[-1]["die.heat"])
# the heat content sum_I C_I T_I = rho c sum_g w_g T_g, so the balance holds to the history's digits
rkcase.check(abs(taken - lost) < 1e-6 * lost, f"the die took {taken:.6f} J, the bar lost {lost:.6f} J")

# Measured: 3.5 % at 0.4 s at the bar's corners, where three films meet (1.4 % at 0.5 mm spacing:
# first order there), 0.56 % at 2 s; the mean within 0.32 %
case, conv = run("slab_convection", "scene_convection.yaml")
rkcase.check(conv["max_error"] < 0.05, f"convection: T^h within {conv['max_error']:.4f} of the product series (< 0.05)")
last = conv["frames"][-1]
rkcase.check(last["max_error"] < 0.01, f"convection: within {last['max_error']:.4f} at {last['time_s']} s (< 0.01)")
worst_mean = max(abs(f["mean_K"] - f["exact_mean_K"]) / 300 for f in conv["frames"])
rkcase.check(worst_mean < 0.005, f"convection: the mean temperature within {worst_mean:.5f} of the exact mean (< 0.005)")

# Measured: 0.12 % of the 100 K step at most (at 4 s); the mean 347.5 K (the step's) kept to 1e-9 K
case, step = run("slab_regions", "scene_regions.yaml")
rkcase.check(step["max_error"] < 0.0025, f"a region's start: T^h within {step['max_error']:.4f} of the step's series (< 0.0025)")
rows = list(csv.DictReader(open(case / "history.csv")))
drift = abs(float(rows[-1]["temperature_mean"]) - float(rows[0]["temperature_mean"]))
rkcase.check(drift < 1e-6 and abs(float(rows[0]["temperature_mean"]) - 347.5) < 0.05,
             f"insulated: the mean temperature {float(rows[0]['temperature_mean']):.4f} K moves {drift:.1e} K")

# Measured: 0.64 % of the 100 K difference (a constant k would give the straight line: 12 K off in the middle)
case, bent = run("slab_conductivity", "scene_conductivity.yaml")
rkcase.check(bent["max_error"] < 0.012, f"k(T): T^h within {bent['max_error']:.4f} of the Kirchhoff steady profile (< 0.012)")

# Measured: 0.086 % of T0 - Ta at most, at 2.5 s (the bar is within a tenth of a kelvin of uniform)
case, rad = run("slab_radiation", "scene_radiation.yaml")
rkcase.check(rad["max_error"] < 0.0015, f"radiation: T^h within {rad['max_error']:.5f} of the lumped closed form (< 0.0015)")

# c(T) and rho(T) tables (scene_tables.yaml: c from 485 down to 375 J/kg K as the bar cools from 600
# K, rho from 8766 up to 8915 kg/m^3). Measured 2026-12-02: the mean within 0.25 % of the lumped ODE
# (the lumped model's own error at Biot 0.02, as with a constant c: 0.23 %); a constant c at the
# table's first value (tried: the table ignored) puts the mean 6.8 % off. The die's heat is the enthalpy the
# bar lost, rho0 V (h(T0) - h(T_mean)), to 1.0e-7 (h is quadratic: the points' spread of 0.8 K about
# the mean); the volume change is rho(T0) / rho(T_mean) - 1 = -1.102 %, over the last 2 s (100 rows: the
# free bar rings about it by up to 8e-4 of itself) to -1.24e-4 / -1.25e-4 of itself at CFL 0.5 / 0.9
# (measured 2026-12-05; the same spread), bound 2.5e-4.
case, tabled = run("slab_tables", "scene_tables.yaml")
rkcase.check(tabled["max_lumped_error"] < 0.005,
             f"c(T), rho(T): the mean within {tabled['max_lumped_error']:.4f} of the lumped ODE (< 0.005)")
row = list(csv.DictReader(open(case / "history.csv")))[-1]
V = json.loads((case / "prep.json").read_text())["volume_m3"]
T_mean = float(row["temperature_mean"])
h = lambda T: 270 * 375 + (T - 270) * (375 + 375 + 110 * (T - 270) / 330) / 2  # int_0^T c, c held below 270 K
rho = lambda T: 8915 + (8766 - 8915) * (T - 270) / 330
lost = 8766 * V * (h(600) - h(T_mean))
rkcase.check(abs(float(row["die.heat"]) / lost - 1) < 4e-7,
             f"c(T): the die took {float(row['die.heat']):.4f} J, the bar's enthalpy fell by {lost:.4f} J")
late = list(csv.DictReader(open(case / "history.csv")))[-100:]
changed = sum(float(r["volume_change"]) for r in late) / len(late)
shrink = sum(rho(600) / rho(float(r["temperature_mean"])) - 1 for r in late) / len(late)
rkcase.check(abs(changed / shrink - 1) < 2.5e-4,
             f"rho(T): the volume changed by {changed:.6f} over the last 2 s, rho(T0) / rho(T) - 1 = {shrink:.6f}")
summary = json.loads((case / "solve.json").read_text())
# measured 2026-12-05: 3.1 % at the default CFL 0.9 (0.36 % at 0.5). The free bar rings as it shrinks,
# its kinetic energy as large as the thermal strain's work, the scale, and each step shortened to land
# on a frame adds to the balance's error (0.22 % at 0.9 with one frame at the end); without the thermal
# strain's work in the balance the error was 2e5 times the scale
rkcase.check(summary["max_energy_error"] < 0.05, f"energy balance with the thermal strain's work: {summary['max_energy_error']:.4f} (< 0.05)")
