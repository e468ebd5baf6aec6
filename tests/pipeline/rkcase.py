"""Shared helpers of the pipeline tests: run the three programs as a user would, read what rkpost wrote."""
import contextlib
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TAYLOR = ROOT / "geometry" / "taylor_bar" / "scene.yaml"
sys.path.insert(0, str(ROOT / "scripts"))  # taylor_metrics, upsetting_check

MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
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
        return self.run(args, **kw)

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


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message)
