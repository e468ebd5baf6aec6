"""Hot upsetting (geometry/upsetting/scene_hot.yaml: C45 at 1150 C, dies at 250 C, Hansel-Spittel with
c(T) and k(T) tables, conduction, die contact conductance, convection and radiation, thermal expansion, shear friction,
a reference update)
at 2.5 mm spacing to 0.3 s of its 1 s stroke:
- the heat balances: the part's heat content change (rho c V times its mean temperature change) is
  the plastic work's heat beta W_p and the friction's work (shear factor 0.3) less the heat the die
  (its conductance and its share of the friction's heat) and the air took, to the history's digits
  (conduction moves heat and keeps it; a reference update projects the temperatures so that it keeps
  the heat content);
- the die chills the part's top: the coolest point sits on it, far below the start, the hottest
  inside, above the start (plastic work);
- the answer does not depend on the thermal update's interval: an update every mechanical step
  against the default (about every 16 steps) gives the same temperatures and heat flows;
- 1, 2 and 3 ranks give the same positions, temperatures and Cockcroft-Latham damage, bitwise, and a
  run stopped at 0.15 s and restarted ends bitwise equal to the uninterrupted one;
- the scene's tracks (tracks.csv) show the die face's centre chilled below the core, and survive the
  restart."""
import csv
import json

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
scene = rkcase.ROOT / "geometry" / "upsetting" / "scene_hot.yaml"
# reference updates at a Green strain of 0.1 (the scene's 0.3 comes after 0.3 s): the temperatures
# must cross them (projected, carried over the ranks, checkpointed)
sets = ["time.end=0.3", "time.output_interval=0.15", "reference_updates.strain=0.1", "damage.cockcroft_latham.critical=0"]
T0, rho, c, beta = 1423.15, 7850.0, 650.0, 0.9


def run(name, ranks, extra=(), restart_at=None):
    case = tools.case(name)
    tools.prep(case, ranks, scene=scene, sets=["discretization.spacing=2.5e-3"])
    if restart_at:
        tools.solve(case, ranks, sets=["time.end=%g" % restart_at] + sets[1:])
        tools.run(["mpirun", "-np", ranks, tools.bin / "rksolve", case, "--quiet", "--restart"] +
                  sum((["--set", s] for s in sets), []))
    else:
        tools.solve(case, ranks, sets=sets + list(extra))
    tools.post(case)
    return case


def last_row(case):
    return list(csv.DictReader(open(case / "history.csv")))[-1]


def final(case):
    frames = sorted((case / "vtk").glob("frame_*.vtu"))
    m = meshio.read(frames[-1])
    order = np.argsort(m.point_data["global_id"].ravel())
    return m.points[order], m.point_data["temperature"].ravel()[order], m.point_data["damage_cockcroft_latham"].ravel()[order]


one = run("hot_r1", 1)
r = last_row(one)
V = json.loads((one / "prep.json").read_text())["volume_m3"]
content = rho * c * V * (float(r["temperature_mean"]) - T0)  # c(T) is 650 J/(kg K) above 900 C, where every point stays
sources = beta * float(r["plastic_work"]) + float(r["friction_work"]) - float(r["die.heat"]) - float(r["heat_to_ambient"])
out = float(r["die.heat"]) + float(r["heat_to_ambient"])
# measured 0 to the printed digits (1e-10 of the heat out); 1e-6 leaves the 10 digits of history.csv
rkcase.check(abs(content - sources) < 1e-6 * out,
             f"heat content change {content:.4f} J = beta W_p + W_friction - Q_die - Q_air = {sources:.4f} J "
             f"(friction {float(r['friction_work']):.3f} J, the die took {r['die.heat']} J)")
x, T, _ = final(one)
top = x[:, 2] > x[:, 2].max() - 0.5e-3  # the particles on the die face (within a fifth of a spacing)
# measured: coolest 1240 K on the die face (the start 1423 K)
rkcase.check(T[top].min() < T0 - 150 and T.argmin() in np.where(top)[0],
             f"the die chilled the top: coolest {T.min():.0f} K, on the top face")
# measured 0.30 K above the start at 0.3 s (15 % reduction): the C45 law's 60 MPa heats the billet
# 1.6 K adiabatically by then, and conduction spreads it toward the chilled face
rkcase.check(float(r["temperature_max"]) > T0 + 0.15, f"plastic work heats the inside: {float(r['temperature_max']):.2f} K")
summary = json.loads((one / "solve.json").read_text())
rkcase.check(summary["reference_updates"] >= 1 and summary["thermal_updates"] < summary["steps"] / 5,
             f"{summary['reference_updates']} reference update(s), {summary['thermal_updates']} thermal updates in {summary['steps']} steps")

every = run("hot_every_step", 1, ["thermal.max_steps_per_update=1"])
e = last_row(every)
# measured 2026-12-02 (C45): mean 0.020 K, coolest point 0.17 K, die heat 4.3e-4, air heat 1.4e-5 apart
# (the explicit step's error; 0.022 K, 0.28 K, 4.5e-4 and 8e-6 with the earlier Johnson-Cook billet);
# the bounds about twice the larger
for key, tol in (("temperature_mean", 0.05), ("temperature_min", 0.7)):
    gap = abs(float(e[key]) - float(r[key]))
    rkcase.check(gap < tol, f"{key}: an update every step and the default agree within {gap:.3f} K (< {tol})")
for key in ("die.heat", "heat_to_ambient"):
    gap = abs(float(e[key]) / float(r[key]) - 1)
    rkcase.check(gap < 1.2e-3, f"{key}: an update every step and the default agree within {gap:.1e} (< 1.2e-3)")

reference = final(one)
for ranks in (2, 3):
    other = final(run(f"hot_r{ranks}", ranks))
    rkcase.check(all(np.array_equal(a, b) for a, b in zip(reference, other)),
                 f"1 and {ranks} ranks give the same positions, temperatures and damage, bitwise")
restarted = final(run("hot_restart", 2, restart_at=0.15))
rkcase.check(all(np.array_equal(a, b) for a, b in zip(reference, restarted)),
             "a run stopped at 0.15 s and restarted ends bitwise equal to the uninterrupted one (damage included)")
# the tracks: the die face chills, the core does not; the restart kept the rows before 0.15 s (at the
# first part's row spacing, as history.csv) and wrote the rest (the tracks' sums over ranks are
# doubles: the last row equal to the 1-rank run's within 1e-9)
rows = {c: list(csv.DictReader(open(c / "tracks.csv"))) for c in (one, tools.work / "hot_restart")}
a, b = rows[one][-1], rows[tools.work / "hot_restart"][-1]
times = [float(r["time"]) for r in rows[tools.work / "hot_restart"]]
rkcase.check(all(t1 > t0 for t0, t1 in zip(times, times[1:])) and
             all(abs(float(a[k]) - float(b[k])) <= 1e-9 * max(1.0, abs(float(a[k]))) for k in a),
             f"tracks.csv: the restarted 2-rank run's {len(times)} rows ascend, its last equal to the 1-rank run's within 1e-9")
rkcase.check(float(a["die_face.temperature"]) < float(a["core.temperature"]) - 100,
             f"the die face's centre at {float(a['die_face.temperature']):.0f} K, the core at {float(a['core.temperature']):.0f} K")
# and they read the frames' temperature at their particles: the conduction's field T^h there with the pending
# plastic heat (the tracks took the points' weighted mean: the die face's centre 1207 K in the tracks against
# 1156 K in the frame at 0.51 s of a probe's run, 2026-12-08); the last row is at the last frame's time
m = meshio.read(sorted((one / "vtk").glob("frame_*.vtu"))[-1])
for name in ("core", "die_face", "equator"):
    at = np.array([float(a[f"{name}.{c}"]) for c in "xyz"])
    i = int(np.argmin(((m.points - at) ** 2).sum(axis=1)))
    T_frame = float(m.point_data["temperature"].ravel()[i])
    rkcase.check(abs(float(a[f"{name}.temperature"]) - T_frame) < 1e-6,
                 f"track {name}: {float(a[name + '.temperature']):.6f} K, the frame at its particle {T_frame:.6f} K")

# A temperature region starts with its thermal strain (the part heated locally from the uniform 1423 K):
# the billet's lower half at 1323 K, 0.02 s. The first step's thermal work counts that strain's jump,
# so the balance holds the elastic energy the region starts with. Measured 2026-12-07 (1 rank, 669
# steps): largest energy error 0.0048; without the jump in the balance the run stopped at step 101 on
# an energy error of 15.6 ("an unstable mode there; reduce time.cfl", which made it worse)
region = tools.case("hot_region")
tools.prep(region, 1, scene=scene, sets=["discretization.spacing=2.5e-3"])
p = tools.solve(region, 1, sets=["time.end=0.02", "time.output_interval=0.01",
                                 "initial_conditions.temperature_regions=[{lo: [-1, -1, -1], hi: [1, 1, 0.005], temperature: 1323.15}]"],
                expect_ok=False)
error = json.loads((region / "solve.json").read_text())["max_energy_error"] if p.returncode == 0 else None
rkcase.check(p.returncode == 0 and error < 0.01, f"a region 100 K below the part: runs, largest energy error {error} (< 0.01) "
             f"{p.stderr.strip()[:200]}")
