"""meshio reads rkpost's .vtu frames as they are: every point-data array of every frame_*.vtu has one
row per point and as many columns as the field has components, and holds bitwise the values of the
ranks' result frames (CASE/results/rank_NNNN/frame_FFFFF.h5, shared/result_frame.hpp), merged by
global id; the points are the frames' positions, the cells the prepared integration cells with their
rank. Read compressed (rkpost's default) and with --uncompressed.

meshio, unlike VTK's reader, recomputes the offsets of the appended arrays itself; a layout that VTK
reads correctly can still give meshio a wrong array under a right name (raw appended data once read
a velocity of 243 x 3 for the 729 particles of the patch cube). Two cases:
1. the patch cube (729 particles, 1 rank, the elastic homogeneous motion of tests/pipeline/essential_bcs.py),
2. the Taylor bar at 2 mm on 2 ranks (119 particles), 8 us, every field nonzero and merged across the
   ranks; also written uncompressed with --fields eq_plastic_strain,von_mises,pressure. That order at
   a particle count of 2 mod 3 makes every array's base64 text exactly 4/3 of its bytes, so the
   pressure's offset in base64 equals the rank's offset in bytes: a reader that re-encodes raw
   appended data and looks the arrays up by offset (meshio 5) swaps those two.
"""
import json
import shutil

import h5py
import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()


def result_frame(case, ranks, frame):
    """The ranks' result frame `frame` merged by global id: {dataset: array with one row per particle}."""
    parts = {}
    for r in range(ranks):
        with h5py.File(case / "results" / f"rank_{r:04d}" / f"frame_{frame:05d}.h5", "r") as f:
            g = f[f"frames/{frame:05d}"]
            for key in g:
                if key not in ("time", "step"):
                    parts.setdefault(key, []).append(np.asarray(g[key]))
            parts.setdefault("rank", []).append(np.full(len(g["global_id"]), r, dtype=np.int64))
    gid = np.concatenate(parts["global_id"]).ravel()
    order = np.argsort(gid)
    n = len(gid)
    return {k: np.concatenate(v).reshape(n, -1)[order] for k, v in parts.items()}


def check_frames(case, ranks, how, fields=None):
    prep = json.loads((case / "prep.json").read_text())
    frames = sorted((case / "vtk").glob("frame_*.vtu"))
    h5 = sorted((case / "results" / "rank_0000").glob("frame_*.h5"))
    rkcase.check(len(frames) == len(h5) >= 3, f"{case.name} ({how}): {len(frames)} frames, one per result frame")
    for path in frames:
        k = int(path.stem.split("_")[1])
        m = meshio.read(path)
        ref = result_frame(case, ranks, k)
        if fields:
            ref = {name: a for name, a in ref.items() if name in fields + ["global_id", "rank", "x"]}
        n = len(m.points)
        rkcase.check(n == prep["particles"] and np.array_equal(ref["global_id"].ravel(), np.arange(n)),
                     f"{path.name}: {n} points, every particle once")
        # the result frame's fields, and with all of them rkpost's own `fold` (post/folds.hpp)
        rkcase.check(set(m.point_data) == set(ref) - {"x"} | ({"fold"} if not fields else set()),
                     f"{path.name}: the point arrays are the result frame's fields ({', '.join(sorted(m.point_data))})")
        wrong = []
        for name, a in m.point_data.items():
            if name == "fold":
                continue
            a = np.asarray(a)
            cols = ref[name].shape[1]
            # (points, components); a one-component array may also come as a vector
            if not (a.shape == (n, cols) or (cols == 1 and a.shape == (n,))):
                wrong.append(f"{name} read as {a.shape} for {n} points of {cols} components")
            # rkpost copies the doubles: equal to the bit, nothing to allow for
            elif not np.array_equal(a.reshape(n, cols), ref[name]):
                wrong.append(f"{name} differs from the result frames' (largest difference "
                             f"{np.abs(a.reshape(n, cols) - ref[name]).max():.3g})")
        rkcase.check(not wrong, f"{path.name}: {len(m.point_data)} point arrays of (points, components), each equal "
                     f"to the result frames'" + "".join(f"; {w}" for w in wrong))
        rkcase.check(np.array_equal(np.asarray(m.points), ref["x"]), f"{path.name}: the points are the frames' positions")
        cells = sum(len(c.data) for c in m.cells)
        rank = np.concatenate([np.asarray(r).ravel() for r in m.cell_data["rank"]])
        rkcase.check(cells == prep["cells"] and len(rank) == cells and sorted(set(rank.tolist())) == list(range(ranks)),
                     f"{path.name}: {cells} cells, each with its rank (0..{ranks - 1})")


def post_both(case, ranks, fields=None):
    tools.post(case)
    check_frames(case, ranks, "compressed")
    shutil.rmtree(case / "vtk")
    tools.run([tools.bin / "rkpost", case, "--quiet", "--no-pictures", "--uncompressed"])
    check_frames(case, ranks, "uncompressed")
    if fields:
        shutil.rmtree(case / "vtk")
        tools.run([tools.bin / "rkpost", case, "--quiet", "--no-pictures", "--uncompressed", "--fields", ",".join(fields)])
        check_frames(case, ranks, f"uncompressed, --fields {','.join(fields)}", fields)


patch = tools.case("patch_cube")
tools.prep(patch, 1, scene=rkcase.ROOT / "tests" / "pipeline" / "data" / "patch_cube" / "scene.yaml")
tools.solve(patch, 1)
post_both(patch, 1)

bar = tools.case("taylor_2ranks")
tools.prep(bar, 2, sets=["discretization.spacing=2e-3"])
rkcase.check(json.loads((bar / "prep.json").read_text())["particles"] % 3 == 2, "the bar has 2 mod 3 particles")
tools.solve(bar, 2, sets=["time.end=8e-6", "time.output_interval=2e-6"])
last = result_frame(bar, 2, 4)
rkcase.check(all(np.abs(a).max() > 0 for a in last.values()), "at 8 us every field of the bar is nonzero somewhere")
post_both(bar, 2, ["eq_plastic_strain", "von_mises", "pressure"])
