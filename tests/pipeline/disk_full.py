"""A full disk stops the whole job with a clear message (no hang, non-zero exit), keeps the last
good checkpoint, and the run restarts from it once there is room.
(1) history.csv on /dev/full (every write fails with ENOSPC); (2) the checkpoint folder on a
300 KiB tmpfs that holds one set of checkpoints but not the next: the run stops, the first set
survives complete, and the case, copied to a disk with room, restarts from it to the end.
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
a = meshio.read(sorted((whole / "vtk").glob("frame_*.vtu"))[-1])
b = meshio.read(sorted((rescued / "vtk").glob("frame_*.vtu"))[-1])
rkcase.check(np.array_equal(a.points, b.points) and np.array_equal(a.point_data["velocity"], b.point_data["velocity"]),
             "restarted after the full disk: final state bitwise equal to an uninterrupted run")
