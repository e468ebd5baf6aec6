"""A missing, foreign (other scene or other prep) or wrong-rank-count subdomain file, and checkpoints swapped between
ranks, stop ALL ranks with one clear
message and a non-zero exit, within seconds (no hang)."""
import shutil
import time

import rkcase

tools = rkcase.tools_from_argv()
coarse = ["discretization.spacing=1.5e-3"]
sets = ["time.end=1e-6"]


def expect_failure(case, ranks, needle, what):
    t0 = time.time()
    p = tools.solve(case, ranks, sets=sets, expect_ok=False, timeout=60)
    took = time.time() - t0
    rkcase.check(p.returncode != 0, f"{what}: non-zero exit ({p.returncode})")
    rkcase.check(needle in p.stderr, f"{what}: message names the problem: {p.stderr.strip().splitlines()[0]}")
    rkcase.check(took < 30, f"{what}: stopped in {took:.1f} s")


case = tools.case("bad_missing")
tools.prep(case, 2, sets=coarse)
(case / "sub" / "rank_0001.h5").unlink()
expect_failure(case, 2, "rank_0001.h5: file not found", "missing rank file")

case = tools.case("bad_foreign")
other = tools.case("bad_other_scene")
tools.prep(case, 2, sets=coarse)
tools.prep(other, 2, sets=["discretization.spacing=1.4e-3"])
shutil.copy(other / "sub" / "rank_0000.h5", case / "sub" / "rank_0000.h5")
shutil.copy(other / "sub" / "rank_0000.h5.fnv1a", case / "sub" / "rank_0000.h5.fnv1a")
expect_failure(case, 2, "was prepared from another scene", "foreign subdomain file")

case = tools.case("bad_count")
tools.prep(case, 2, sets=coarse)
expect_failure(case, 3, "prepared for 2 ranks but the job has 3", "wrong rank count")

case = tools.case("bad_version")
tools.prep(case, 1, sets=coarse)
(case / "sub" / "rank_0000.h5").write_bytes(b"not hdf5 at all")
expect_failure(case, 1, "checksum mismatch: the file is corrupt or truncated", "garbage subdomain file")

# rank files of two preps of the same scene (another partitioner): each passes its own checks, and the
# first overlap exchange crashed with MPI_ERR_TRUNCATE and no rksolve message
case = tools.case("bad_mixed")
other = tools.case("bad_other_partition")
tools.prep(case, 2, sets=coarse)
tools.run([tools.bin / "rkprep", rkcase.TAYLOR, "--ranks", 2, "--out", other, "--quiet", "--partitioner", "metis-recursive",
           "--set", coarse[0]])
for name in ("rank_0001.h5", "rank_0001.h5.fnv1a"):
    shutil.copy(other / "sub" / name, case / "sub" / name)
expect_failure(case, 2, "sub/rank_0001.h5 was written by another rkprep run than", "rank files of two preps")

# a finished run's checkpoints swapped between its ranks (equal counts of particles and points on each): the restart
# ran rank 0 on rank 1's state, stopped on a symmetry-plane check and overwrote the run's good last frame
case = tools.case("bad_swapped_checkpoints")
tools.prep(case, 2, sets=coarse)
tools.solve(case, 2, sets=["time.end=2e-6", "time.output_interval=1e-6"])
last = case / "results" / "rank_0000" / "frame_00002.h5"
before = last.read_bytes()
for suffix in ("", ".previous"):
    a, b = (case / "checkpoint" / f"rank_000{r}.h5{suffix}" for r in (0, 1))
    if a.exists():
        a.rename(case / "checkpoint" / "swap"), b.rename(a), (case / "checkpoint" / "swap").rename(b)
p = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", case, "--quiet", "--restart", "--set", "time.end=3e-6"], expect_ok=False,
              timeout=60)
rkcase.check(p.returncode != 0 and "the checkpoint of rank 1, here read by rank 0" in p.stderr and last.read_bytes() == before,
             f"swapped checkpoints are refused by file, the last frame kept: {p.stderr.strip().splitlines()[:2]}")

# a folder by the lock file's name (made by hand): the case could not be locked, and two runs wrote one case,
# their frames mixed
case = tools.case("bad_lock")
tools.prep(case, 1, sets=coarse)
(case / ".rksolve.lock").mkdir()
expect_failure(case, 1, ".rksolve.lock is not a lock file", "a folder where the lock file goes")
