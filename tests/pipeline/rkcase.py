"""Shared helpers of the pipeline tests: run the three programs as a user would, read what rkpost wrote."""
import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TAYLOR = ROOT / "geometry" / "taylor_bar" / "scene.yaml"
sys.path.insert(0, str(ROOT / "scripts"))  # taylor_metrics, upsetting_check

# ctest runs two tests at once on two cores, each mpirun believing the cores its own (measured
# 2026-12-07): its ranks yield the core while they wait for a message (two 2-rank runs whose waiting
# ranks spin took 1.7-1.8x the wall time of the same runs yielding: 10.3 / 11.2 s against 6.0 / 6.5 s;
# one run alone the same within the noise), and they are not bound to cores (mpirun binds a 1-rank
# run to core 0, so two of them at once shared it: 2.09 / 2.18 s against 1.29 / 1.25 s unbound).
# A job that fails costs no wait: after a rank's non-zero exit mpirun waits odls_base_sigkill_timeout
# (1 s by default) twice even when every rank has ended (`mpirun -np 1 false`: 2.1 s against 0.09 s at 0),
# and the suite runs 32 jobs meant to fail (2026-12-07). Their ranks have finished MPI_Finalize by then.
# The one test of a signal's grace (Ctrl-C) sets Open MPI's default back.
MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
    "OMPI_MCA_mpi_yield_when_idle": "1",
    "OMPI_MCA_hwloc_base_binding_policy": "none",
    "OMPI_MCA_odls_base_sigkill_timeout": "0",
}


class Tools:
    def __init__(self, bin_dir, work_dir):
        self.bin = Path(bin_dir)
        self.work = Path(work_dir)
        self.work.mkdir(parents=True, exist_ok=True)
        self.env = dict(os.environ, **MPI_ENV)

    def run(self, args, expect_ok=True, timeout=900):
        """The program's CompletedProcess. Past `timeout` (or on an interrupt) it is killed with everything
        it started, its process group (mpirun's ranks, xvfb-run's X server), and TimeoutExpired is raised
        with its stderr."""
        start = time.monotonic()
        proc = subprocess.Popen([str(a) for a in args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env=self.env, start_new_session=True)
        try:
            out, err = proc.communicate(timeout=timeout)
        except BaseException as e:
            with contextlib.suppress(ProcessLookupError):  # (an interrupt just after the group ended)
                os.killpg(proc.pid, signal.SIGKILL)
            out, err = proc.communicate()
            if isinstance(e, subprocess.TimeoutExpired):
                e.stderr = err
            raise
        p = subprocess.CompletedProcess(proc.args, proc.returncode, out, err)
        # each program's wall time in the test's log (ctest's LastTest.log): where a slow test spends it
        line = " ".join(map(str, args)).replace(f"{self.bin}/", "").replace(f"{self.work}/", "")
        print(f"ran in {time.monotonic() - start:.2f} s, exit {p.returncode}: {line}")
        if expect_ok and p.returncode != 0:
            raise AssertionError(f"{' '.join(map(str, args))} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
        return p

    def case(self, name):
        path = self.work / name
        shutil.rmtree(path, ignore_errors=True)
        return path

    def prep(self, case, ranks=1, scene=TAYLOR, sets=(), **kw):
        args = [self.bin / "rkprep", scene, "--ranks", ranks, "--out", case, "--quiet"]
        for s in sets:
            args += ["--set", s]
        return self.run(args, **kw)

    def solve(self, case, ranks=1, sets=(), **kw):
        args = ["mpirun", "-np", ranks, self.bin / "rksolve", case, "--quiet"]
        for s in sets:
            args += ["--set", s]
        p = self.run(args, **kw)
        if p.returncode == 0:
            check_phases(Path(case) / "solve.json")
        return p

    def post(self, case, **kw):
        # no pictures: the suite checks them once (rkpost_paraview), not in every test
        return self.run([self.bin / "rkpost", case, "--quiet", "--no-pictures"], **kw)


def tools_from_argv():
    import argparse
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    return Tools(a.bin, a.work)


def check_phases(summary_path):
    """Every phase's time in solve.json within the run's wall time: a timer read against a start it never
    had (the dwell's first phase once read 54 144 s, the clock's epoch) is a wrong report, not a slow run."""
    summary = json.loads(Path(summary_path).read_text())
    wall = summary["wall_s"]
    for name, t in summary["phases"].items():
        if not 0 <= t["min_s"] <= t["max_s"] <= 1.001 * wall + 0.01:
            raise AssertionError(f"{summary_path}: phase {name} took {t['min_s']}..{t['max_s']} s of a {wall} s run")


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message)
