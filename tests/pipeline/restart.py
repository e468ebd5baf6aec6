"""Checkpoint and restart lose nothing: (1) a run stopped at 4 us and restarted to 8 us
ends bitwise equal to the uninterrupted run, frames and all; (2) a rank killed with SIGKILL mid-run
stops the whole job quickly, leaves the last good checkpoint, and the restart from it ends bitwise
equal to the uninterrupted run; (3) a job killed between its ranks' checkpoint writes (one rank a
checkpoint behind) restarts from the newest step every rank holds, bitwise; a new run drops an
older run's checkpoints; with no checkpoint, or a time.end before it, --restart is one clear error.
The bar runs with bulk viscosity on (its q and the last step's det F are in the checkpoint)."""
import os
import re
import shutil
import signal
import subprocess
import time

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
prep = tools.case("restart_prep")
tools.prep(prep, 2, sets=["discretization.spacing=1.2e-3", "bulk_viscosity.quadratic=1.5", "bulk_viscosity.linear=0.06"])


def copy(name):
    dst = tools.case(name)
    shutil.copytree(prep, dst)
    return dst


def final(case):
    tools.post(case)
    frames = sorted((case / "vtk").glob("frame_*.vtu"))
    m = meshio.read(frames[-1])
    order = np.argsort(m.point_data["global_id"].ravel())
    return len(frames), m.points[order], m.point_data["velocity"][order], m.point_data["eq_plastic_strain"][order]


def same(a, b):
    return a[0] == b[0] and all(np.array_equal(x, y) for x, y in zip(a[1:], b[1:]))


out = ["time.output_interval=2e-6"]
whole = copy("restart_whole")
tools.solve(whole, 2, sets=["time.end=8e-6"] + out)
split = copy("restart_split")
tools.solve(split, 2, sets=["time.end=4e-6"] + out)
# the restart names only its new end: the run's own --set values (its 2-us frames) come from
# checkpoint/run.yaml (a restart used to drop them and went on at the scene's frame interval)
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", split, "--quiet", "--restart", "--set", "time.end=8e-6"])
reference = final(whole)
rkcase.check(same(reference, final(split)), "stopped at 4 us and restarted to 8 us: bitwise equal, same frames")
# a key that would change the run half-way is refused by name, by --set or by an edit of the case's scene
changed = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", split, "--quiet", "--restart", "--set", "time.end=12e-6",
                     "--set", "material.yield_stress=100e6"], expect_ok=False)
rkcase.check(changed.returncode != 0 and "--set: key 'material.yield_stress' = 100000000 where the run started with "
             "400000000" in changed.stderr, f"a restart that changes the material: {changed.stderr.strip()[:300]}")
resolved = split / "scene.resolved.yaml"
text = resolved.read_text()
resolved.write_text(text.replace("cfl: 0.9", "cfl: 0.5", 1))
edited = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", split, "--quiet", "--restart", "--set", "time.end=12e-6"],
                   expect_ok=False)
rkcase.check(edited.returncode != 0 and "scene.resolved.yaml: key 'time.cfl' = 0.5 where the run started with 0.9" in edited.stderr,
             f"a restart after an edit of the case's scene: {edited.stderr.strip()[:300]}")
resolved.write_text(text)
# and a plain restart goes on to the last restart's end (8 us): run.yaml keeps a restart's own --set values too
# (it kept the first run's 4 us, below the checkpoint's 8 us, and the plain restart was refused)
again = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", split, "--quiet", "--restart"], expect_ok=False)
rkcase.check(again.returncode == 0, f"a plain restart after a restart to 8 us: {again.stderr.strip()[:300]}")

# A new run in a case that holds an older, different run's checkpoints (CFL 0.5, to 8 us) must not
# restart from them: run to 4 us, restart to 8 us, and get the whole run (the older 8-us checkpoint
# would be the newest step every rank holds).
stale = copy("restart_stale")
tools.solve(stale, 2, sets=["time.end=8e-6", "time.cfl=0.5"] + out)
tools.solve(stale, 2, sets=["time.end=4e-6"] + out)
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", stale, "--quiet", "--restart", "--set", "time.end=8e-6",
           "--set", "time.output_interval=2e-6"])
rkcase.check(same(reference, final(stale)), "a new run drops an older run's checkpoints: its restart ends bitwise equal")

# CFL 0.03 (12 755 steps, 2.8 s on 2026-12-04): at larger steps this run can end before the test has found its
# ranks to kill or its Ctrl-C has reached them (at 0.5 it took 0.65 s; at 0.1, 3 827 steps, 0.87 s once
# the solver had got faster, on 2026-12-04, and the Ctrl-C came after the end)
long = ["time.end=16e-6", "time.output_interval=4e-6", "output.checkpoint_steps=50", "time.cfl=0.03"]
whole = copy("kill_whole")
tools.solve(whole, 2, sets=long)
killed = copy("kill_killed")
args = ["mpirun", "-np", "2", str(tools.bin / "rksolve"), str(killed), "--quiet"]
for s in long:
    args += ["--set", s]
job = subprocess.Popen(args, env=tools.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
ckpt = killed / "checkpoint" / "rank_0001.h5"
deadline = time.time() + 120
while not ckpt.exists() and time.time() < deadline and job.poll() is None:
    time.sleep(0.05)
time.sleep(0.3)
pids = subprocess.run(["pgrep", "-f", f"^\\S*bin/rksolve {killed}"], capture_output=True, text=True).stdout.split()
rkcase.check(job.poll() is None and len(pids) == 2, f"the run is going with a checkpoint ({len(pids)} ranks)")
os.kill(int(pids[-1]), signal.SIGKILL)
t0 = time.time()
try:
    job.wait(timeout=60)
except subprocess.TimeoutExpired:
    job.kill()
    raise AssertionError("the job hangs after a rank was killed")
rkcase.check(job.returncode != 0, f"a killed rank stops the job (exit {job.returncode}) in {time.time() - t0:.1f} s")
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", killed, "--quiet", "--restart"] +
          sum((["--set", s] for s in long), []))
rkcase.check(same(final(whole), final(killed)), "restarted after SIGKILL: final state bitwise equal to the uninterrupted run")

# Ctrl-C (SIGINT to mpirun, which passes it on as SIGTERM): every rank stops at the same step after a
# checkpoint and a frame, with one message saying how to go on; the restart ends bitwise equal.
interrupted = copy("interrupted")
args = ["mpirun", "-np", "2", str(tools.bin / "rksolve"), str(interrupted)] + sum((["--set", s] for s in long), [])
# mpirun's own grace (Open MPI's default, 1 s) between passing the signal on and SIGKILL: the suite sets 0
grace = dict(tools.env, OMPI_MCA_odls_base_sigkill_timeout="1")
job = subprocess.Popen(args, env=grace, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
ckpt = interrupted / "checkpoint" / "rank_0001.h5"
deadline = time.time() + 120
while not ckpt.exists() and time.time() < deadline and job.poll() is None:  # well into the run
    time.sleep(0.05)
job.send_signal(signal.SIGINT)
_, err = job.communicate(timeout=60)
said = [ln for ln in err.splitlines() if "rksolve: error" in ln]
m = re.search(r"interrupted at step (\d+), t = ([-+0-9.eE]+) s: checkpoint and last frame written; `rksolve \S+ --restart` "
              r"goes on from here", said[0]) if said else None
rkcase.check(job.returncode != 0 and len(said) == 1 and m is not None, f"Ctrl-C: exit {job.returncode}, {said}")
steps = {int(re.search(r"\(0,0\):\s*(\d+)", tools.run(["h5dump", "-d", "clock/integers", p]).stdout)[1])
         for p in (interrupted / "checkpoint").glob("rank_*.h5")}
rkcase.check(steps == {int(m[1])}, f"both ranks' checkpoints are at the interrupted step {m[1]}: {steps}")
p = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", interrupted, "--restart"] + sum((["--set", s] for s in long), []))
rkcase.check(f"restarted from the checkpoint of step {m[1]}" in p.stdout, "the restart says where it goes on from")
rkcase.check(same(final(whole), final(interrupted)), "restarted after Ctrl-C: final state bitwise equal")

# Killed between the ranks' writes: rank 1's newest checkpoint is the one before rank 0's (the
# uninterrupted run's case, whose last two checkpoints are 50 steps or less apart).
behind = tools.case("kill_behind")
shutil.copytree(whole, behind)
p = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", behind, "--quiet", "--restart", "--set", "time.end=8e-6"],
              expect_ok=False)
rkcase.check(p.returncode != 0 and "key 'time.end' = 8e-06 s is before the checkpoint's t = 1.6e-05 s" in p.stderr,
             f"a restart to a time.end before its checkpoint is refused: {p.stderr.strip().splitlines()[0]}")
ck = behind / "checkpoint"
steps = {p.name: int(re.search(r"\(0,0\):\s*(\d+)", tools.run(["h5dump", "-d", "clock/integers", p]).stdout)[1])
         for p in sorted(ck.glob("rank_*"))}  # the step of each file
os.replace(ck / "rank_0001.h5.previous", ck / "rank_0001.h5")
tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", behind, "--quiet", "--restart"] + sum((["--set", s] for s in long), []))
rkcase.check(same(final(whole), final(behind)),
             f"rank 1 a checkpoint behind (steps {steps}): restarted from the older step, bitwise equal")
empty = copy("restart_nothing")
p = tools.run(["mpirun", "-np", 2, tools.bin / "rksolve", empty, "--quiet", "--restart"], expect_ok=False, timeout=120)
rkcase.check(p.returncode != 0 and "no complete checkpoint" in p.stderr and "Traceback" not in p.stderr
             and "checkpoint/rank_0000.h5 and its .previous are missing or unreadable" in p.stderr,
             f"--restart without a checkpoint: {p.stderr.strip().splitlines()[0] if p.stderr.strip() else p.returncode}")

# Wall-clock checkpoints: with step checkpoints off, a checkpoint still appears while the run goes on.
clock = copy("clock_checkpoint")
args = ["mpirun", "-np", "2", str(tools.bin / "rksolve"), str(clock), "--quiet", "--set", "time.end=16e-6",
        "--set", "output.checkpoint_steps=0", "--set", "output.checkpoint_minutes=0.002"]
job = subprocess.Popen(args, env=tools.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
ckpt = clock / "checkpoint" / "rank_0000.h5"
deadline = time.time() + 120
while not ckpt.exists() and time.time() < deadline and job.poll() is None:
    time.sleep(0.02)
running = job.poll() is None
job.wait(timeout=300)
rkcase.check(running and ckpt.exists() and job.returncode == 0,
             "output.checkpoint_minutes = 0.002 (0.12 s): a checkpoint was written while the run was going")

# While a run goes on in a case (its own job, long enough for every check, stopped after them; before, the
# checks ran against the Ctrl-C job above, which could end first on a loaded machine):
# - a second rksolve into it is refused (two runs' history rows interleaved and both exited 0);
# - so is an rkprep --force (it removed the running solve's results and lock under it);
# - rkpost merges the frames so far and says the run is still going (it said the run did not finish);
# and the running job goes on untouched.
busy = copy("busy")
job = subprocess.Popen(["mpirun", "-np", "2", str(tools.bin / "rksolve"), str(busy), "--set", "time.end=1e-3",
                        "--set", "time.cfl=0.03", "--set", "time.output_interval=1e-6"],
                       env=grace, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
deadline = time.time() + 120
while not (busy / "results" / "rank_0001").exists() and time.time() < deadline and job.poll() is None:
    time.sleep(0.05)
second = tools.solve(busy, 2, sets=long, expect_ok=False)
rkcase.check(second.returncode != 0 and "another rksolve or rkprep is writing this case" in second.stderr,
             f"a second run into the running case: exit {second.returncode}, {second.stderr.strip()[:200]}")
reprep = tools.run([tools.bin / "rkprep", rkcase.TAYLOR, "--ranks", 2, "--out", busy, "--force", "--quiet",
                    "--set", "discretization.spacing=1.2e-3"], expect_ok=False)
rkcase.check(reprep.returncode != 0 and "another rksolve or rkprep is writing this case" in reprep.stderr,
             f"rkprep --force into the running case: exit {reprep.returncode}, {reprep.stderr.strip()[:200]}")
during = tools.post(busy)
rkcase.check("rksolve is still running in it" in during.stderr, f"rkpost during the run: {during.stderr.strip()[:200]}")
rkcase.check(job.poll() is None and (busy / "sub").exists(), "the running job goes on through the three")
job.send_signal(signal.SIGINT)  # (stopped as a user would: mpirun's SIGKILL could leave its ranks running)
job.communicate(timeout=60)
