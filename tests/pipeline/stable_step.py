"""The stable step from the highest frequency of the discrete system (time.stable_step = frequency,
solver/highest_frequency.hpp): dt = cfl x 2 / omega_max, omega_max^2 the largest eigenvalue of M^-1 K by
power iteration on the elastic tangent.
- Sharp, on the slender clamped beam (geometry/beam, elastic, 2 025 particles), whose highest mode the
  step must respect: at 1.05 of 2 / omega_max the beam's free end blows up within 100 steps (measured
  2026-12-03: the pressure check stops it at step 32), at 0.95 it runs 4 000 steps with its energy
  conserved. So the estimate is within 5 % of the true limit, from both sides. The cells' estimate at
  the same 1.05 runs stably (it is 1.16x below the limit on this beam): the stop is the frequency's.
- Faster at the same answer, on the Taylor bar (1 369 particles, 80 us): the cells' estimate is
  2.2-3.6x below the limit there, so CFL 0.9 of 2 / omega_max takes 3 991 steps against the cells'
  10 705 (measured 2026-12-03) for r_f 7.112 / L_f 21.466 mm against 7.116 / 21.473 mm.
- Bitwise on 2 ranks and through a restart after a kill (the power iteration's sums are in fixed point
  and its vector is checkpointed), history.csv included."""
import re
import shutil

import json
import sys

import meshio
import numpy as np

import rkcase

sys.path.insert(0, str(rkcase.ROOT / "scripts"))
from taylor_metrics import metrics  # noqa: E402

tools = rkcase.tools_from_argv()
FREQUENCY = "time.stable_step=frequency"


def solve_json(case):
    return json.loads((case / "solve.json").read_text())


# --- sharp: the beam past and below the limit
beam = tools.case("beam_prep")
tools.prep(beam, 1, scene=rkcase.ROOT / "geometry" / "beam" / "scene.yaml")


def beam_run(name, sets, expect_ok=True):
    case = tools.case(name)
    shutil.copytree(beam, case)
    return case, tools.solve(case, 1, sets=sets, expect_ok=expect_ok)


past, p = beam_run("beam_past", [FREQUENCY, "time.cfl=1.05", "time.end=2e-4", "time.output_interval=1e-4"], expect_ok=False)
stopped = re.search(r"at step (\d+)", p.stderr)
reason = next((line for line in p.stderr.splitlines() if "error:" in line), "")
rkcase.check(p.returncode != 0 and stopped and int(stopped.group(1)) <= 100 and "warning: time.cfl = 1.05" in p.stderr,
             f"1.05 x 2 / omega_max: warned at the start, stopped at step {stopped.group(1) if stopped else '?'} "
             f"({reason[:200]})")

cells, _ = beam_run("beam_cells", ["time.stable_step=cells", "time.cfl=1.05", "time.end=2e-4", "time.output_interval=1e-4"])
steps_cells = solve_json(cells)["steps"]
rkcase.check(steps_cells >= 300, f"the cells' estimate at cfl 1.05: {steps_cells} steps, stable (it lies below the limit)")

# 4 000 steps at 0.95: the energy stays within 1e-4 of the initial kinetic energy (measured 2026-12-03 at
# 0.9 over 40 ms, 96 800 steps: at most 4.7e-5)
below, _ = beam_run("beam_below", [FREQUENCY, "time.cfl=0.95", "time.end=1.75e-3", "time.output_interval=0.875e-3"])
s = solve_json(below)
rkcase.check(s["steps"] >= 4000 and s["max_energy_error"] < 1e-4,
             f"0.95 x 2 / omega_max: {s['steps']} steps, largest energy error {s['max_energy_error']:.2e}")

# --- the Taylor bar: the same answer in fewer steps
bar = tools.case("bar")
tools.prep(bar, 1)
tools.solve(bar, 1, sets=[FREQUENCY])
tools.post(bar)
m = metrics(bar)
s = solve_json(bar)
# against the cells' estimate's 7.116 / 21.473 mm in 10 705 steps (2026-12-03): the differences measured,
# 0.004 and 0.007 mm, doubled
rkcase.check(abs(m["footprint_radius_mm"] - 7.116) < 0.01 and abs(m["final_length_mm"] - 21.473) < 0.015,
             f"Taylor bar: r_f {m['footprint_radius_mm']:.4f} mm, L_f {m['final_length_mm']:.4f} mm "
             "(the cells' estimate: 7.116, 21.473)")
rkcase.check(s["steps"] < 4400, f"Taylor bar: {s['steps']} steps (the cells' estimate: 10 705)")
# solve.json says which estimate ran and how far the cells' lay below it at the end (2.73 measured with
# the probe of 2026-12-03 on the cells' run at 76-79 us)
rkcase.check(s["stable_step"] == "frequency" and 2.5 < s["step_ratio"] < 3.0,
             f"solve.json: stable_step {s['stable_step']}, step_ratio {s['step_ratio']:.3f}")


# --- 2 ranks and a restart, bitwise
def last_arrays(case):
    """Every point field of the last frame (rkpost's merge), by global id."""
    tools.post(case)
    frame = meshio.read(sorted((case / "vtk").glob("frame_*.vtu"))[-1])
    order = np.argsort(frame.point_data["global_id"].ravel())
    return {k: v[order] for k, v in frame.point_data.items() if k != "rank"}


SETS = ["time.end=40e-6", "time.output_interval=5e-6"]
runs = {}
for ranks in (1, 2):
    case = tools.case(f"bar_{ranks}")
    tools.prep(case, ranks, sets=[FREQUENCY])  # in the case's scene, so the restart reads it too
    tools.solve(case, ranks, sets=SETS)
    runs[ranks] = case
a, b = last_arrays(runs[1]), last_arrays(runs[2])
rkcase.check(a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a),
             "2 ranks: every particle array of the frames bitwise equal to 1 rank")
# Killed after a mid-run checkpoint and restarted: the 0.6 mm bar to 12 us takes 173 steps (measured),
# checkpoints at step 100 and at the end; the last removed, the one of step 100 in its place. (Its
# history row at step 100 prints 8.487935217e-06, below the checkpoint's time: a restart that kept
# rows by their printed time wrote that row twice.)
whole = tools.case("bar_whole")
tools.prep(whole, 2, sets=[FREQUENCY, "discretization.spacing=0.6e-3"])
SETS = ["time.end=12e-6", "time.output_interval=6e-6", "output.checkpoint_steps=100"]
tools.solve(whole, 2, sets=SETS)
killed = tools.case("bar_killed")
shutil.copytree(whole, killed)
for newest in (killed / "checkpoint").glob("rank_*.h5"):
    newest.with_name(newest.name + ".previous").replace(newest)
(killed / "solve.json").unlink()
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", killed, "--quiet", "--restart"] + sum((["--set", s] for s in SETS), []))
b, c = last_arrays(whole), last_arrays(killed)
steps = solve_json(whole)["steps"]
rkcase.check(100 < steps < 200 and solve_json(killed)["steps"] == steps and b.keys() == c.keys()
             and all(np.array_equal(b[k], c[k]) for k in b),
             f"restarted from step 100 of {steps}: every particle array of the last frame bitwise equal")
rkcase.check((killed / "history.csv").read_bytes() == (whole / "history.csv").read_bytes(),
             "restarted from step 100: history.csv bitwise equal")
