"""The answer does not depend on the rank count (DESIGN.md section 4): a coarse Taylor bar
for a few hundred steps on 1, 2, 3 and 4 ranks (oversubscribed) gives, per global id, bitwise the
same positions, velocities and plastic strain as on one rank. Each rank writes only its owned
particles and rkpost merges every particle exactly once, with `rank` = its owner. Both EBC methods, and
nodal integration (its smoothing-cell faces cross the partition), and multi-rate steps (the classes of the
particles shared over the partition summed as counts)."""
import json

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
sets = ["time.end=8e-6", "time.output_interval=4e-6"]


def frames_of(method, prep_sets, solve_sets):
    frames = {}
    for ranks in (1, 2, 3, 4):
        case = tools.case(f"ranks_{ranks}_{method.replace(' ', '_')}")
        tools.prep(case, ranks, sets=["discretization.spacing=1.2e-3", *prep_sets])
        tools.solve(case, ranks, sets=sets + solve_sets)
        tools.post(case)
        steps = json.loads((case / "solve.json").read_text())["steps"]
        vtu = meshio.read(case / "vtk" / "frame_00002.vtu")
        order = np.argsort(vtu.point_data["global_id"].ravel())
        frames[ranks] = {k: np.asarray(v).reshape(len(order), -1)[order] for k, v in vtu.point_data.items()}
        frames[ranks]["x"] = np.asarray(vtu.points)[order]
        owners = set(np.unique(frames[ranks]["rank"]).tolist())
        rkcase.check(owners == set(range(ranks)), f"{method}, {ranks} ranks: every rank owns particles ({steps} steps)")
    return frames


for method, prep_sets, solve_sets in (("nodal", ["discretization.ebc_method=nodal"], []),
                                      ("transformation", ["discretization.ebc_method=transformation"], []),
                                      ("nodal integration", ["discretization.integration=nodal"], []),
                                      ("multi-rate steps", [], ["time.subcycling=16"])):
    frames = frames_of(method, prep_sets, solve_sets)
    base = frames[1]
    rkcase.check(base["eq_plastic_strain"].max() > 0.1, f"{method}: the run is well into plastic flow")
    for ranks in (2, 3, 4):
        for key in ("x", "velocity", "eq_plastic_strain", "displacement", "von_mises"):
            same = np.array_equal(frames[ranks][key], base[key])
            diff = np.abs(frames[ranks][key] - base[key]).max()
            rkcase.check(same, f"{method}, {ranks} ranks: {key} bitwise equal to 1 rank (max diff {diff:.3g})")
