"""rkpost --partitioned: each frame as one .vtu piece per solver rank and a .pvtu listing them, which
ParaView reads in parallel. The Taylor bar at 1.6 mm on 3 ranks (399 particles), 8 us:
1. the .pvtu is what ParaView 5.11 expects (PUnstructuredGrid, every array of the pieces declared
   with its type and components, pieces by relative path) and case.pvd lists the .pvtu files;
2. read by ParaView's own reader (pvpython), every frame holds, apart from the points marked
   vtkGhostType = 1, exactly the merged .vtu's particles once each, with the same positions and
   values to the bit, and the same cells on the same particles with the same ranks; the ghost points
   are copies of their owners' particles;
3. `mpirun -np 2 pvbatch --symmetric` reads the last frame in parallel, each process its share of the
   pieces (without a display), and under Xvfb renders a picture that is not blank;
4. --fields limits the pieces' arrays; a prepared case (not solved) is written as pieces too;
5. a rank's frame file missing: that frame is reported once, naming the file, and skipped (no .pvtu,
   no pieces), the others written.
pvbatch without --symmetric (only process 0 runs the script) hangs at exit in this install (Debian's
ParaView 5.11 with Open MPI 4.1: process 0 waits in MPI_Barrier in vtkProcessModule::Finalize), so
every process runs the script."""
import json
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import matplotlib.image as mpimg
import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
PIPELINE = rkcase.ROOT / "tests" / "pipeline"
RANKS = 3


def paraview_read(case):
    """Every dataset of CASE/vtk/case.pvd as ParaView reads it (tests/pipeline/pv_dump.py)."""
    p = subprocess.run(["pvpython", str(PIPELINE / "pv_dump.py"), str(case)], capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        raise AssertionError(f"pvpython failed:\n{p.stdout}\n{p.stderr}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def cells_by_id(d, gid):
    """The dataset's cells as (rank, its points' global ids in order), sorted: comparable across layouts."""
    conn, off = np.asarray(d["connectivity"]), np.asarray(d["offsets"])
    ranks = np.asarray(d["cell_data"]["rank"]).ravel()
    return sorted((int(ranks[c]), tuple(gid[conn[off[c]:off[c + 1]]].tolist())) for c in range(len(off) - 1))


def declared(path):
    """The .pvtu's arrays {section: [(name, type, components)]} and its pieces."""
    grid = ET.parse(path).getroot().find("PUnstructuredGrid")
    arrays = {s: [(a.get("Name"), a.get("type"), a.get("NumberOfComponents")) for a in grid.find(s).iter("PDataArray")]
              for s in ("PPointData", "PCellData", "PPoints")}
    return arrays, [p.get("Source") for p in grid.iter("Piece")]


def held(path):
    """A piece's arrays {section: [(name, type, components)]}."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    return {s: [(a.get("Name"), a.get("type"), a.get("NumberOfComponents")) for a in piece.find(s).iter("DataArray")]
            for s in ("PointData", "CellData", "Points")}


case = tools.case("bar_partitioned")
tools.prep(case, RANKS, sets=["discretization.spacing=1.6e-3"])
tools.solve(case, RANKS, sets=["time.end=8e-6", "time.output_interval=4e-6"])
prep = json.loads((case / "prep.json").read_text())
tools.post(case)  # merged: the reference
merged = tools.case("bar_merged")
(merged / "vtk").mkdir(parents=True)
for f in (case / "vtk").iterdir():
    shutil.copy(f, merged / "vtk")
p = tools.run([tools.bin / "rkpost", case, "--no-pictures", "--partitioned"])
rkcase.check("written as one piece per rank" in p.stdout, f"rkpost --partitioned: {p.stdout.strip()}")
vtk = case / "vtk"

# 1. the files
listed = [d.get("file") for d in ET.parse(vtk / "case.pvd").getroot().iter("DataSet")]
rkcase.check(listed == [f"frame_{f:05d}.pvtu" for f in range(3)] and not list(vtk.glob("frame_*.vtu")),
             f"case.pvd lists the .pvtu files, no merged .vtu left: {listed}")
for name in listed:
    arrays, pieces = declared(vtk / name)
    stem = name.removesuffix(".pvtu")
    rkcase.check(pieces == [f"{stem}/rank_{r:04d}.vtu" for r in range(RANKS)] and all((vtk / s).is_file() for s in pieces),
                 f"{name}: one piece per rank, relative paths: {pieces}")
    reference = meshio.read(merged / "vtk" / f"{stem}.vtu")
    names = [a[0] for a in arrays["PPointData"]]
    rkcase.check(names == list(reference.point_data) + ["vtkGhostType"] and ("vtkGhostType", "UInt8", "1") in arrays["PPointData"]
                 and arrays["PCellData"] == [("rank", "Int64", "1")] and arrays["PPoints"] == [("Points", "Float64", "3")],
                 f"{name}: declares the merged file's point arrays and vtkGhostType (UInt8), cell rank, Float64 points")
    wrong = [s for s in pieces if held(vtk / s) != {"PointData": arrays["PPointData"], "CellData": arrays["PCellData"],
                                                    "Points": arrays["PPoints"]}]
    rkcase.check(not wrong, f"{name}: every piece holds exactly the declared arrays, types and components")

# 2. ParaView reads the pieces as the merged file
pv_pieces, pv_merged = paraview_read(case), paraview_read(merged)
rkcase.check(len(pv_pieces["datasets"]) == len(pv_merged["datasets"]) == 3 and pv_pieces["times"] == pv_merged["times"],
             f"ParaView reads 3 frames of both at the same times {pv_pieces['times']}")
for d, m in zip(pv_pieces["datasets"], pv_merged["datasets"]):
    ghost = np.asarray(d["point_data"]["vtkGhostType"]).ravel() & 1
    gid = np.asarray(d["point_data"]["global_id"]).ravel()
    own = np.flatnonzero(ghost == 0)
    order = own[np.argsort(gid[own])]
    n = len(m["points"])
    rkcase.check(n == prep["particles"] and len(own) == n and np.array_equal(gid[order], np.arange(n))
                 and ghost.sum() > 0 and len(gid) == n + ghost.sum(),
                 f"{d['file']}: {len(gid)} points, {ghost.sum()} of them ghosts: each of the {n} particles once")
    same = np.array_equal(np.asarray(d["points"])[order], np.asarray(m["points"]))
    copies = np.array_equal(np.asarray(d["points"])[ghost == 1], np.asarray(m["points"])[gid[ghost == 1]])
    for name, values in m["point_data"].items():
        a, b = np.asarray(d["point_data"][name]), np.asarray(values)
        same &= np.array_equal(a[order], b)
        copies &= np.array_equal(a[ghost == 1], b[gid[ghost == 1]])
    rkcase.check(same, f"{d['file']}: positions and all {len(m['point_data'])} point arrays bitwise the merged file's")
    rkcase.check(copies, f"{d['file']}: the ghost points carry their owners' positions and values")
    rkcase.check(d["cells"] == m["cells"] == prep["cells"] and d["cell_types"] == m["cell_types"]
                 and cells_by_id(d, gid) == cells_by_id(m, np.asarray(m["point_data"]["global_id"]).ravel()),
                 f"{d['file']}: the same {d['cells']} cells on the same particles, each with its rank")

# 3. in parallel: 2 pvbatch processes share the 3 pieces (read without a display), then render the part
last = vtk / listed[-1]
top = float(np.asarray(pv_merged["datasets"][-1]["point_data"]["eq_plastic_strain"]).max())
p = tools.run(["mpirun", "-np", "2", "--oversubscribe", "pvbatch", "--symmetric", PIPELINE / "pv_parallel_render.py", last,
               "-", top], timeout=300)
read = sorted((json.loads(ln.split(" ", 1)[1]) for ln in p.stdout.splitlines() if ln.startswith("piece ")),
              key=lambda r: r["process"])
rkcase.check([r["process"] for r in read] == [0, 1] and all(r["processes"] == 2 and r["cells"] > 0 for r in read)
             and sum(r["cells"] for r in read) == prep["cells"]
             and sum(r["points"] - r["ghost_points"] for r in read) == prep["particles"]
             and sorted(k for r in read for k in r["cell_ranks"]) == list(range(RANKS)),
             f"mpirun -np 2 pvbatch --symmetric: each process read its own pieces, together every cell and particle once: {read}")
# The render needs an X server (Xvfb): under the suite's load it refused a process's window in 1 run of
# 6 to 3 runs of 3 (2026-12-02, "bad X server connection", before any of this software's work), and
# an attempt now and then hangs (twice in the runs of `make test` of 2026-12-07), so it is tried
# up to five times, each given RENDER_S seconds (an attempt took 5.2-5.6 s alone, six of six, and the
# whole test 14-26 s in the suite), then killed with everything it started (rkcase.Tools.run); a run
# whose every attempt the X server refused says so and checks the read only, and any other failure of
# every attempt fails the test.
RENDER_S = 40


def render(png):
    """One attempt: its exit status (None when it hung) and its stderr."""
    try:
        p = tools.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "mpirun", "-np", "2", "--oversubscribe", "pvbatch",
                       "--symmetric", PIPELINE / "pv_parallel_render.py", last, png, top], expect_ok=False, timeout=RENDER_S)
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired as e:
        return None, (e.stderr or "") + f"\n(hung: killed after {RENDER_S} s)"


png = case / "parallel.png"
refused = 0
for attempt in range(5):
    png.unlink(missing_ok=True)
    status, stderr = render(png)
    if status == 0 and png.exists():
        break
    refused += "bad X server connection" in stderr
    print(f"pvbatch attempt {attempt + 1} failed ({status}): {stderr[-600:]}")
    time.sleep(3 * (attempt + 1))
if refused == 5:
    print("WARNING: the X server refused every attempt's window under this load; the parallel render was not checked")
else:
    rkcase.check(status == 0, f"mpirun -np 2 pvbatch --symmetric rendered (exit {status})")
    img = mpimg.imread(png)
    colours = len(np.unique(img.reshape(-1, img.shape[-1]), axis=0))
    rkcase.check(img.shape[:2] == (480, 640) and colours > 50 and (img[..., :3] < 0.9).any(axis=-1).mean() > 0.01,
                 f"{png.name}: {img.shape[1]}x{img.shape[0]}, {colours} colours, the part drawn")

# 4. --fields, and a prepared case
tools.run([tools.bin / "rkpost", case, "--quiet", "--no-pictures", "--partitioned", "--frames", "-1",
           "--fields", "eq_plastic_strain"])
arrays, _ = declared(vtk / "frame_00002.pvtu")
rkcase.check([a[0] for a in arrays["PPointData"]] == ["global_id", "eq_plastic_strain", "rank", "vtkGhostType"],
             f"--fields eq_plastic_strain: {[a[0] for a in arrays['PPointData']]}")
fresh = tools.case("bar_prepared")
tools.prep(fresh, RANKS, sets=["discretization.spacing=1.6e-3"])
tools.run([tools.bin / "rkpost", fresh, "--quiet", "--partitioned"])
pieces = [meshio.read(p) for p in sorted((fresh / "vtk" / "frame_00000").glob("rank_*.vtu"))]
owned = [np.asarray(m.point_data["global_id"])[np.asarray(m.point_data["vtkGhostType"]) == 0] for m in pieces]
rkcase.check(len(pieces) == RANKS and np.array_equal(np.sort(np.concatenate(owned)), np.arange(prep["particles"]))
             and sum(len(c.data) for m in pieces for c in m.cells) == prep["cells"],
             f"a prepared case: {RANKS} pieces at t = 0, every particle owned once, every cell once")

# 5. a rank's frame missing
missing = case / "results" / "rank_0001" / "frame_00001.h5"
missing.unlink()
p = tools.run([tools.bin / "rkpost", case, "--no-pictures", "--partitioned"], expect_ok=False)
said = [ln for ln in p.stderr.splitlines() if ln.strip()]
rkcase.check(p.returncode == 0 and len(said) == 1 and "frame 1 skipped" in said[0] and str(missing) in said[0]
             and "missing" in said[0], f"the missing frame is one message naming the file: {said}")
listed = [d.get("file") for d in ET.parse(vtk / "case.pvd").getroot().iter("DataSet")]
rkcase.check(listed == ["frame_00000.pvtu", "frame_00002.pvtu"] and not (vtk / "frame_00001.pvtu").exists()
             and not (vtk / "frame_00001").exists(), f"frame 1 skipped, neither .pvtu nor pieces left; written: {listed}")

# The scripts read merged frames: on a partitioned case one message naming the case and the way out (they
# failed with an IndexError or meshio's "Could not deduce file format ... .pvtu")
p = tools.run([sys.executable, rkcase.ROOT / "scripts" / "taylor_metrics.py", case], expect_ok=False)
rkcase.check(p.returncode != 0 and "its frames are one piece per rank (rkpost --partitioned)" in p.stderr
             and "Traceback" not in p.stderr, f"taylor_metrics.py on a partitioned case: {p.stderr.strip()}")
