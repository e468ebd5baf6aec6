"""A full disk stops the whole job with a clear message (no hang, non-zero exit), keeps the last
good checkpoint, and the run restarts from it once there is room.
(1) history.csv on /dev/full (every write fails with ENOSPC); (2) the checkpoint folder on a
300 KiB tmpfs that holds one set of checkpoints but not the next: the run stops, the first set
survives complete, and the case, copied to a disk with room, restarts from it to the end.
Every other file the programs write fails the same way, one error naming it: history.csv that
cannot be made (3 ranks; rank 0 writes it), a full disk on rank 2 only (its frames; 3 ranks, every
rank stops with rank 2's message; and on 1 rank, none crashes), a restart whose history has other columns, solve.json,
prep.json, rkpost's .pvd, a frame's .vtu that cannot take its name, and report.md.
The tests run as root (the pipeline tests' MPI settings, tests/pipeline/rkcase.py), here and in CI,
so the tmpfs mounts: a mount that fails is a failure of this test, not a reason to skip half of it."""
import os
import shutil
import subprocess
import time

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
prep = tools.case("full_prep")
tools.prep(prep, 2, sets=["discretization.spacing=1.5e-3"])
sets = ["time.end=8e-6", "time.output_interval=0.5e-6", "output.checkpoint_steps=20"]


def stops(args, expect, what):
    """args must stop within 60 s (no rank left waiting) with the programs' error exit, 1 (a crash or a
    signal gives another), and one error holding `expect` (a string, or a tuple of strings all in it)."""
    t0 = time.time()
    p = subprocess.run(["timeout", "60"] + [str(a) for a in args], capture_output=True, text=True, env=tools.env)
    errors = [line for line in p.stderr.splitlines() if "error:" in line]
    expects = (expect,) if isinstance(expect, str) else expect
    rkcase.check(p.returncode == 1 and len(errors) == 1 and all(e in errors[0] for e in expects),
                 f"{what}: exit {p.returncode} in {time.time() - t0:.1f} s, {errors or p.stderr.strip()[-300:]}")


def solve_args(case, ranks, more=()):
    return ["mpirun", "-np", ranks, tools.bin / "rksolve", case, "--quiet"] + sum((["--set", s] for s in sets), []) + list(more)


prep3 = tools.case("full_prep3")
tools.prep(prep3, 3, sets=["discretization.spacing=1.5e-3"])
case = tools.case("full_history_dir")
shutil.copytree(prep3, case)
(case / "history.csv").mkdir()  # rank 0 cannot create it (the tests run as root: a mode would not stop it)
stops(solve_args(case, 3), "history.csv: cannot write the history file", "history.csv cannot be made, 3 ranks")

# A full disk on one rank: its results folder on a 64 KiB tmpfs, so one of its first two frames fails. On 3 ranks
# (rank 2's) every rank stops with rank 2's message. Before HDF5's exit clean-up was turned off the failing
# rank then crashed in it on the file whose close had failed (exit 139): always on 1 rank, in about half
# the 3-rank runs (when mpirun had not yet ended it), so the 1-rank run is the one that catches it.
def full_rank_folder(prepared, ranks, rank):
    folder = f"rank_{rank:04d}"
    subprocess.run(["umount", str(tools.work / f"full_{ranks}_{folder}" / "results" / folder)], capture_output=True)  # stale
    case = tools.case(f"full_{ranks}_{folder}")
    shutil.copytree(prepared, case)
    mnt = case / "results" / folder
    mnt.mkdir(parents=True)
    mount = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(mnt)], capture_output=True, text=True)
    rkcase.check(mount.returncode == 0, f"a 64 KiB tmpfs mounted on {folder}'s results (mount: exit {mount.returncode} "
                 f"{mount.stderr.strip()})")
    try:
        stops(solve_args(case, ranks), (f"results/{folder}/frame_", ".h5.tmp: the file could not be completed (disk full?)"),
              f"a full disk on {folder} only, {ranks} ranks")
    finally:
        subprocess.run(["umount", str(mnt)])


full_rank_folder(prep3, 3, 2)
prep1 = tools.case("full_prep1")
tools.prep(prep1, 1, sets=["discretization.spacing=1.5e-3"])
full_rank_folder(prep1, 1, 0)

case = tools.case("full_summary")
shutil.copytree(prep, case)
os.symlink("/dev/full", case / "solve.json")
stops(solve_args(case, 2), "solve.json: cannot write (No space left on device)", "solve.json on a full disk")

case = tools.case("full_prep_json")
case.mkdir()
os.symlink(tools.work / "no_such_folder" / "prep.json", case / "prep.json")  # dangling: no case there yet
stops([tools.bin / "rkprep", rkcase.TAYLOR, "--ranks", 1, "--out", case, "--quiet", "--set", "discretization.spacing=2e-3"],
      "prep.json: cannot write (No such file or directory)", "prep.json that cannot be made")

case = tools.case("full_pvd")
shutil.copytree(prep, case)
(case / "vtk").mkdir()
os.symlink("/dev/full", case / "vtk" / "case.pvd")
stops([tools.bin / "rkpost", case, "--quiet", "--no-pictures"], "case.pvd: cannot write (No space left on device)",
      "rkpost's .pvd on a full disk")
os.remove(case / "vtk" / "case.pvd")
os.remove(case / "vtk" / "frame_00000.vtu")
(case / "vtk" / "frame_00000.vtu").mkdir()  # the written frame cannot be renamed over it
stops([tools.bin / "rkpost", case, "--quiet", "--no-pictures"], "frame_00000.vtu: cannot write (renaming",
      "a frame's .vtu that cannot take its name")
rkcase.check(not list((case / "vtk").glob("*.tmp")), "no partial .vtu left behind")

case = tools.case("full_history")
shutil.copytree(prep, case)
os.symlink("/dev/full", case / "history.csv")
t0 = time.time()
p = tools.solve(case, 2, sets=sets, expect_ok=False, timeout=120)
rkcase.check(p.returncode != 0 and "history.csv: write failed (disk full?)" in p.stderr,
             f"history on a full disk: {p.stderr.strip().splitlines()[0] if p.stderr.strip() else p.returncode}")
rkcase.check(time.time() - t0 < 60, f"stopped in {time.time() - t0:.1f} s")

subprocess.run(["umount", str(tools.work / "full_tmpfs" / "checkpoint")], capture_output=True)  # a stale mount
case = tools.case("full_tmpfs")
shutil.copytree(prep, case)
mnt = case / "checkpoint"
mnt.mkdir()
mount = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=300k", "tmpfs", str(mnt)], capture_output=True, text=True)
rkcase.check(mount.returncode == 0, f"a 300 KiB tmpfs mounted on the checkpoint folder (mount: exit {mount.returncode} "
             f"{mount.stderr.strip()})")
try:
    p = tools.solve(case, 2, sets=sets, expect_ok=False, timeout=120)
    rkcase.check(p.returncode != 0 and ("disk full" in p.stderr or "cannot" in p.stderr),
                 f"checkpoints on a full tmpfs: {p.stderr.strip().splitlines()[0] if p.stderr.strip() else p.returncode}")
    rescued = tools.case("full_rescued")
    shutil.copytree(case, rescued)
finally:
    subprocess.run(["umount", str(mnt)])
ckpts = sorted((rescued / "checkpoint").glob("rank_*.h5"))
rkcase.check(len(ckpts) == 2, "both ranks kept a complete checkpoint")
rkcase.check(not list((rescued / "checkpoint").glob("*.tmp")), "no partial checkpoint left behind")
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", rescued, "--quiet", "--restart"] + sum((["--set", s] for s in sets), []))
tools.post(rescued)
whole = tools.case("full_whole")
shutil.copytree(prep, whole)
tools.solve(whole, 2, sets=sets)
tools.post(whole)

# a restart into a history.csv of other columns (as another scene's run writes it): rank 0 finds
# it, and every rank stops with its message
columns = tools.case("full_columns")
shutil.copytree(whole, columns)
rows = (columns / "history.csv").read_text().splitlines()
(columns / "history.csv").write_text("\n".join([rows[0] + ",floor.force"] + [r + ",0" for r in rows[1:]]) + "\n")
stops(solve_args(columns, 2, ["--restart"]), "history.csv: written with other columns",
      "a restart whose history has other columns")
os.remove(columns / "report.md")
os.symlink("/dev/full", columns / "report.md")
stops([tools.bin / "rkpost", columns, "--quiet", "--no-pictures"], "report.md: cannot write (No space left on device)",
      "report.md on a full disk")
a = meshio.read(sorted((whole / "vtk").glob("frame_*.vtu"))[-1])
b = meshio.read(sorted((rescued / "vtk").glob("frame_*.vtu"))[-1])
rkcase.check(np.array_equal(a.points, b.points) and np.array_equal(a.point_data["velocity"], b.point_data["velocity"]),
             "restarted after the full disk: final state bitwise equal to an uninterrupted run")

# past the file-size limit (ulimit -f) a write fails with a message, not SIGXFSZ's silent kill (exit 153; rkprep
# left its lock and a half-written rank file, rkpost a .tmp)
limited = tools.case("file_size_limit")
shutil.copytree(whole, limited)
p = tools.run(["bash", "-c", f"ulimit -f 4; exec '{tools.bin / 'rkpost'}' '{limited}' --quiet --no-pictures"], expect_ok=False)
rkcase.check(p.returncode == 1 and "write failed (disk full?)" in p.stderr, f"rkpost past ulimit -f: exit {p.returncode}, {p.stderr.strip()}")
