"""Every process feature at once (geometry/upsetting/scene_combined.yaml: hot C45 with conduction, die
conductance, convection, radiation and thermal expansion; a crank press with shear friction; a second
body pushed against the billet; the three damage criteria; the part's contact with itself; reference
updates; tracked points; a flow-line plane; the die fill), 0.04 s of the crank's stroke at 2.5 mm
spacing (185 + 64 particles, 4 163 steps, measured 2026-12-03):
- every feature is at work: the die moved and pushes, the bodies touch, the temperature spread, each
  damage criterion grew, the die is partly filled, the part's reference was updated;
- 3 ranks give bitwise the fields of every frame (positions, velocities, temperatures, damage,
  stresses), the tracks and the die's fill and load fields of 1 rank;
- a run killed after its checkpoint at step 3000 (past several reference updates) and restarted ends
  bitwise equal to the uninterrupted one, tracks and history included."""
import csv
import json
import shutil

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
SCENE = rkcase.ROOT / "geometry" / "upsetting" / "scene_combined.yaml"
SETS = ["output.checkpoint_steps=3000"]  # a mid-run checkpoint, after several reference updates


def frames(case):
    """Every frame's point fields by global id, and the die frames' cell fields, after rkpost."""
    tools.post(case)
    out = {}
    for vtu in sorted((case / "vtk").glob("frame_*.vtu")):
        m = meshio.read(vtu)
        order = np.argsort(m.point_data["global_id"].ravel())
        for k, v in m.point_data.items():
            if k != "rank":
                out[(vtu.name, k)] = np.asarray(v)[order]
        out[(vtu.name, "x")] = np.asarray(m.points)[order]
    for vtu in sorted((case / "vtk").glob("die_*.vtu")):
        m = meshio.read(vtu)
        for k, v in m.cell_data.items():
            out[(vtu.name, k)] = np.concatenate([np.asarray(b) for b in v])
    return out


def same(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


runs = {}
for ranks in (1, 3):
    case = tools.case(f"combined_{ranks}")
    tools.prep(case, ranks, scene=SCENE)
    tools.solve(case, ranks, sets=SETS)
    runs[ranks] = case
one = runs[1]
solve = json.loads((one / "solve.json").read_text())
last = list(csv.DictReader(open(one / "history.csv")))[-1]
rkcase.check(solve["reference_updates"] >= 5 and float(last["die.stroke"]) > 2e-3 and float(last["die.force"]) > 0
             and float(last["die.filled"]) > 0.1,
             f"at work: {solve['reference_updates']} reference updates, the die {1e3 * float(last['die.stroke']):.2f} mm "
             f"down at {float(last['die.force']) / 1e3:.1f} kN, {100 * float(last['die.filled']):.1f} % of it filled")
rows = list(csv.DictReader(open(one / "history.csv")))
touching = sum(float(r["part_contacts"]) > 0 for r in rows)
rkcase.check(touching > len(rows) // 2, f"the insert against the billet: particles in contact in {touching} of {len(rows)} rows")
rkcase.check(float(last["temperature_max"]) - float(last["temperature_min"]) > 5
             and all(float(last[f"damage_{c}_max"]) > 0.01 for c in ("cockcroft_latham", "brozzo", "oyane")),
             f"temperatures {float(last['temperature_min']):.1f}-{float(last['temperature_max']):.1f} K, damage "
             + ", ".join(f"{c} {float(last[f'damage_{c}_max']):.3f}" for c in ("cockcroft_latham", "brozzo", "oyane")))

a, b = frames(one), frames(runs[3])
rkcase.check(same(a, b) and (one / "tracks.csv").read_bytes() == (runs[3] / "tracks.csv").read_bytes(),
             f"3 ranks: {len(a)} fields of the frames and die frames, and the tracks, bitwise equal to 1 rank")

# killed after step 3000: the last checkpoint removed, the one of step 3000 in its place
killed = tools.case("combined_killed")
shutil.copytree(runs[3], killed)
for newest in (killed / "checkpoint").glob("rank_*.h5"):
    newest.with_name(newest.name + ".previous").replace(newest)
(killed / "solve.json").unlink()
tools.run(["mpirun", "-np", 3, tools.bin / "rksolve", killed, "--quiet", "--restart"] + sum((["--set", s] for s in SETS), []))
c = frames(killed)
rkcase.check(same(b, c) and (killed / "tracks.csv").read_bytes() == (runs[3] / "tracks.csv").read_bytes()
             and (killed / "history.csv").read_bytes() == (runs[3] / "history.csv").read_bytes(),
             "restarted from step 3000: every field, the tracks and the history bitwise equal")
