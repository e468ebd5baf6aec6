"""What users open and look at: rkpost's VTK files read back by ParaView's own readers
through pvpython, the pictures rendered off-screen by pvbatch, and report.md.

A 2-rank case with a die (the sliding block on its floor): every frame of case.pvd, read by
ParaView, has the particles with exactly the values of the ranks' result files (point count, field
names, values bitwise), the integration cells as hexahedra with the rank of each, and the die as
triangles at its position; --frames and --fields limit what is written; bad options are one clear
error; the pictures are real images; report.md holds the key numbers."""
import json
import subprocess

import h5py
import matplotlib.image as mpimg
import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
data = rkcase.ROOT / "tests" / "pipeline" / "data" / "sliding_block"
case = tools.case("block")
tools.prep(case, 2, scene=data / "scene.yaml")
tools.solve(case, 2, sets=["time.end=1e-4", "time.output_interval=5e-5"])
tools.post(case)


def paraview_read(case):
    p = subprocess.run(["pvpython", str(rkcase.ROOT / "tests" / "pipeline" / "pv_dump.py"), str(case)],
                       capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        raise AssertionError(f"pvpython failed:\n{p.stdout}\n{p.stderr}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def rank_files(case, frame, ranks=2):
    """The ranks' result frame merged by global id: what rkpost must have written."""
    merged = {}
    for r in range(ranks):
        with h5py.File(case / "results" / f"rank_{r:04d}" / f"frame_{frame:05d}.h5", "r") as f:
            g = f[f"frames/{frame:05d}"]
            for key in g:
                if not key.startswith("die_"):  # the particles' fields (the dies' are per triangle)
                    merged.setdefault(key, []).append(np.asarray(g[key]))
            merged.setdefault("rank", []).append(np.full(len(g["global_id"]), r))
    order = np.argsort(np.concatenate(merged["global_id"]).ravel())
    return {k: np.concatenate(v)[order] for k, v in merged.items() if k not in ("time", "step")}


pv = paraview_read(case)
parts = [d for d in pv["datasets"] if d["part"] == 0]
dies = [d for d in pv["datasets"] if d["part"] == 1]
rkcase.check(len(parts) == 3 and len(pv["times"]) == 3, f"ParaView reads case.pvd: {len(parts)} frames at times {pv['times']}")
rkcase.check(pv["blocks"] == ["part", "floor"], f"ParaView names the blocks by what they are: {pv['blocks']}")
rkcase.check(len(dies) == len(parts) and all(d["cells"] > 0 and d["cell_types"] == [5] for d in dies),
             f"the die 'floor' is in every frame as {dies[0]['cells']} triangles")
fields = {"global_id": 1, "displacement": 3, "velocity": 3, "eq_plastic_strain": 1, "von_mises": 1, "pressure": 1,
          "stress": 6, "rank": 1}
for k, d in enumerate(parts):
    ref = rank_files(case, k)
    n = len(ref["global_id"])
    # the result frames' fields, and rkpost's own `fold` (none in this elastic block)
    rkcase.check(len(d["points"]) == n and set(d["point_data"]) == set(fields) | {"fold"}
                 and not np.asarray(d["point_data"]["fold"]).any(),
                 f"frame {k}: {n} particles, point fields {sorted(d['point_data'])}")
    same = np.array_equal(np.asarray(d["points"]), ref["x"].reshape(-1, 3))
    for name in fields:
        same &= np.array_equal(np.asarray(d["point_data"][name]).reshape(n, -1), ref[name].reshape(n, -1))
    rkcase.check(same, f"frame {k}: positions and every field bitwise equal to the ranks' result files")
    rkcase.check(d["cell_types"] == [12] and sorted(set(d["cell_data"]["rank"])) == [0, 1],
                 f"frame {k}: {d['cells']} integration cells as hexahedra, coloured by rank 0 and 1")
prep = json.loads((case / "prep.json").read_text())
rkcase.check(parts[0]["cells"] == prep["cells"], f"every integration cell once ({prep['cells']})")
stress = np.asarray(parts[-1]["point_data"]["stress"])
pressure = np.asarray(parts[-1]["point_data"]["pressure"]).ravel()
vm = np.asarray(parts[-1]["point_data"]["von_mises"]).ravel()
scale = np.abs(stress).max()
rkcase.check(scale > 1e6 and np.allclose(-stress[:, :3].mean(axis=1), pressure, rtol=0, atol=1e-9 * scale),
             f"the stress tensor (up to {scale / 1e6:.1f} MPa) gives the pressure field: -tr(sigma)/3 = p")
s = stress - stress[:, :3].mean(axis=1, keepdims=True) * np.array([1, 1, 1, 0, 0, 0])
vm_of_mean = np.sqrt(1.5 * ((s[:, :3] ** 2).sum(axis=1) + 2 * (s[:, 3:] ** 2).sum(axis=1)))
rkcase.check(np.all(vm_of_mean <= vm * (1 + 1e-9) + 1e-9 * scale),
             "and the von Mises stress of the particle's tensor never exceeds its von_mises (a convex function of "
             "the projected stresses)")

# --frames and --fields limit what is written
tools.run([tools.bin / "rkpost", case, "--quiet", "--frames", "-1", "--fields", "eq_plastic_strain,stress"])
pv = paraview_read(case)
rkcase.check(len(pv["datasets"]) == 2 and pv["datasets"][0]["file"] == "frame_00002.vtu"
             and set(pv["datasets"][0]["point_data"]) == {"global_id", "eq_plastic_strain", "stress", "rank"},
             "--frames -1 --fields eq_plastic_strain,stress: the last frame and the die, with those fields")
for args, expected in ((["--fields", "strain"], "--fields: 'strain' is not a field"),
                       (["--frames", "7"], "--frames: '7' is not a frame of this case")):
    p = tools.run([tools.bin / "rkpost", case] + args, expect_ok=False)
    rkcase.check(p.returncode != 0 and expected in p.stderr, f"rkpost {' '.join(args)}: {p.stderr.strip()}")

# rkpost makes the plots and pictures itself (ParaView off-screen), before its report lists them
p = tools.run([tools.bin / "rkpost", case, "--quiet"])
made = sorted(f.name for f in (case / "plots").glob("*.png"))
# (the floor does not move: no force against stroke, no press section)
rkcase.check(made == ["energies.png", "part_ep_00000.png", "part_ep_00002.png", "part_rank_00000.png", "part_rank_00002.png"]
             and "![part_ep_00002](plots/part_ep_00002.png)" in (case / "report.md").read_text()
             and "Press force" not in (case / "report.md").read_text(),
             f"rkpost made the plots and pictures and report.md shows them: {made}")
# the pictures at a chosen size
p = tools.run([rkcase.ROOT / "scripts" / "pvbatch_offscreen.sh", rkcase.ROOT / "scripts" / "pictures.py", case,
               "--frames", "0,-1", "--size", "640x480"])
for name in ("part_ep_00000", "part_ep_00002", "part_rank_00002"):
    png = case / "plots" / f"{name}.png"
    img = mpimg.imread(png)
    colours = len(np.unique(img.reshape(-1, img.shape[-1]), axis=0))
    rkcase.check(img.shape[:2] == (480, 640) and png.stat().st_size > 10_000 and colours > 50,
                 f"{png.name}: {img.shape[1]}x{img.shape[0]}, {png.stat().st_size} bytes, {colours} colours")
# the colour scales as ParaView drew them: the frame at rest on the run's scale (0 to the largest
# plastic strain of the frames shown, at least 1e-3 so that an elastic run as this one reads 0 to
# 0.001, not 0 to 1e-38), the ranks as categories with a legend entry each
drawn = {d["file"]: d for d in json.loads((case / "plots" / "pictures.json").read_text())["pictures"]}
last_ep = float(meshio.read(case / "vtk" / "frame_00002.vtu").point_data["eq_plastic_strain"].max())
rkcase.check(drawn["part_ep_00000.png"]["scale"] == drawn["part_ep_00002.png"]["scale"]
             and drawn["part_ep_00000.png"]["scale"] == [0, max(last_ep, 1e-3)],
             f"the frame at rest coloured on the run's scale: {drawn['part_ep_00000.png']}, largest strain {last_ep}")
rkcase.check(all(drawn[f"part_rank_{f}.png"].get("categories") == [f"rank {r}" for r in range(prep["ranks"])]
                 for f in ("00000", "00002")) and prep["ranks"] == 2,
             f"the ranks drawn as categories: {drawn['part_rank_00002.png']}")

# the report: rkpost again, now that the pictures exist
tools.post(case)
report = (case / "report.md").read_text()
solve = json.loads((case / "solve.json").read_text())
for text in (f"{solve['steps']} steps", str(prep["particles"]), "energy balance", "part_ep_00002.png", "floor.force"):
    rkcase.check(text in report, f"report.md holds '{text}'")
