"""Each program on its own: --help and --version, and a clear error with a non-zero exit on bad use; the
same for the scripts that read a case (scripts/), unless RK_SCRIPTS=skip (the sanitizer run: they run no
sanitized code)."""
import os

import rkcase

tools = rkcase.tools_from_argv()
scripts_too = os.environ.get("RK_SCRIPTS") != "skip"
for prog in ("rkprep", "rksolve", "rkpost"):
    p = tools.run([tools.bin / prog, "--help"])
    wants = [prog, "--quiet"] + (["--set"] if prog != "rkpost" else [])
    rkcase.check(all(w in p.stdout for w in wants), f"{prog} --help names {', '.join(wants)}")
    p = tools.run([tools.bin / prog, "--version"])
    rkcase.check(p.stdout.startswith(f"{prog} (rkforge)"), f"{prog} --version: {p.stdout.strip()}")

p = tools.run([tools.bin / "rkprep", tools.work / "nope.yaml", "--out", tools.work / "x"], expect_ok=False)
rkcase.check(p.returncode != 0 and "nope.yaml: scene file not found" in p.stderr, "rkprep: missing scene")
# a folder where a file belongs is said to be one (it read as "internal error: basic_filebuf::underflow")
p = tools.run([tools.bin / "rkprep", tools.work, "--out", tools.work / "x"], expect_ok=False)
rkcase.check(p.returncode != 0 and f"{tools.work}: a folder, not a scene file" in p.stderr and "internal error" not in p.stderr,
             f"rkprep: a folder for the scene: {p.stderr.strip()}")
p = tools.run([tools.bin / "rkpost", tools.work / "not_a_case"], expect_ok=False)
rkcase.check(p.returncode != 0 and "prep.json: not found" in p.stderr, "rkpost: not a case directory")
case = tools.case("cli_bad_set")
tools.prep(case, 1, sets=["discretization.spacing=1.5e-3"])
p = tools.solve(case, 1, sets=["discretization.dilation=3"], expect_ok=False)
rkcase.check(p.returncode != 0 and "re-run rkprep" in p.stderr, "rksolve refuses a prep-side --set")
p = tools.solve(case, 1, sets=["time.cfl=abc"], expect_ok=False)
rkcase.check(p.returncode != 0 and "'time.cfl' must be a number" in p.stderr, "rksolve: bad --set value")
p = tools.run([tools.bin / "rkprep", rkcase.TAYLOR, "--ranks", "0", "--out", tools.work / "x"], expect_ok=False)
rkcase.check(p.returncode != 0 and "--ranks: 0 is not a number of ranks (a whole number, at least 1)" in p.stderr
             and len(p.stderr) < 200, f"rkprep --ranks 0: {p.stderr.strip()}")

# an --out that cannot take files is refused before any meshing, with one message naming it. The
# tests run as root, whom a chmod does not stop: a folder under a regular file cannot be made, and
# sysfs takes no new file even from root.
blocker = tools.work / "a_file"
blocker.write_text("not a folder\n")
unwritable = [(blocker / "case", "cannot create the case folder")]
if os.path.isdir("/sys/kernel"):
    unwritable.append(("/sys/kernel", "cannot write in the case folder"))
for out, says in unwritable:
    p = tools.run([tools.bin / "rkprep", rkcase.TAYLOR, "--out", out], expect_ok=False)
    rkcase.check(p.returncode != 0 and f"rkprep: error: {out}: {says}" in p.stderr and "internal error" not in p.stderr
                 and "mesh" not in p.stdout and len(p.stderr.strip().splitlines()) == 1,
                 f"rkprep --out {out}: refused before meshing: {p.stderr.strip()}")

# a new prep never lies beside another case's results: refused without --force, replaced with it
tools.solve(case, 1, sets=["time.end=1e-6"])
again = [tools.bin / "rkprep", rkcase.TAYLOR, "--ranks", 1, "--out", case, "--quiet", "--set", "discretization.spacing=1.5e-3"]
p = tools.run(again, expect_ok=False)
rkcase.check(p.returncode != 0 and "holds a case already (sub, prep.json, scene.resolved.yaml, results, checkpoint, "
             "history.csv, solve.json)" in p.stderr and "--force" in p.stderr and (case / "solve.json").exists(),
             f"rkprep into a solved case is refused, nothing touched: {p.stderr.strip()}")
tools.run(again + ["--force"])
left = sorted(e.name for e in case.iterdir())
rkcase.check(left == ["prep.json", "scene.resolved.yaml", "sub"], f"rkprep --force: only the new prep is left ({left})")

# the bench's machine probe: one JSON object of positive rates, and a clear error on bad use
p = tools.run([tools.bin / "rkmachine", "--seconds", "0.02"])
m = __import__("json").loads(p.stdout)
rates = list(m["triad_gb_per_s"].values()) + [m["gflop_per_s_this_build"]]
rkcase.check(len(rates) == 5 and all(r > 0 for r in rates), f"rkmachine: bandwidths and peak {rates}")
rkcase.check(m["build_vector_bits"] in (128, 256, 512), f"rkmachine: the build's vectors are {m['build_vector_bits']} bits")
p = tools.run([tools.bin / "rkmachine", "--bogus"], expect_ok=False)
rkcase.check(p.returncode == 2 and "unknown argument '--bogus'" in p.stderr, "rkmachine: bad argument")

# rkpost on a case prepared and not solved: the discretization to look at before solving (particles
# with the initial velocity, cells by rank, the dies at t = 0), exit 0
import meshio  # noqa: E402
import numpy as np  # noqa: E402
fresh = tools.case("prepared_only")
tools.prep(fresh, 2, scene=rkcase.ROOT / "geometry" / "upsetting" / "scene.yaml", sets=["discretization.spacing=2.5e-3"])
p = tools.run([tools.bin / "rkpost", fresh], expect_ok=False)
prep = __import__("json").loads((fresh / "prep.json").read_text())
part = meshio.read(fresh / "vtk" / "frame_00000.vtu")
rkcase.check(p.returncode == 0 and "is prepared, not solved" in p.stdout and len(part.points) == prep["particles"]
             and len(part.cells[0].data) == prep["cells"] and sorted(np.unique(part.cell_data["rank"][0])) == [0, 1]
             and (fresh / "vtk" / "die_die_00000.vtu").exists() and not (fresh / "report.md").exists(),
             f"rkpost on a prepared case: {len(part.points)} particles, {len(part.cells[0].data)} cells on ranks 0 and 1, "
             "the die at t = 0")

# two solved cases for the scripts below: the Taylor bar to 1 us, and the upsetting with friction
# (2.5 mm, 1.2 ms: 11 % height reduction, about 3 s)
tools.solve(case, 1, sets=["time.end=1e-6"])
tools.post(case)
upset = tools.case("upsetting_friction")
tools.prep(upset, 1, scene=rkcase.ROOT / "geometry" / "upsetting" / "scene_friction.yaml",
           sets=["discretization.spacing=2.5e-3"])
tools.solve(upset, 1, sets=["time.end=1.2e-3"])
tools.post(upset)
# options that name nothing or nothing known: refused, the case untouched (--frames "" wrote an empty case.pvd, exit 0)
pvd = (upset / "vtk" / "case.pvd").read_bytes()
p = tools.run([tools.bin / "rkpost", upset, "--frames", ""], expect_ok=False)
rkcase.check(p.returncode != 0 and "--frames: '' names no frame" in p.stderr and (upset / "vtk" / "case.pvd").read_bytes() == pvd,
             f"rkpost --frames '': {p.stderr.strip()}")
p = tools.run([tools.bin / "rkprep", rkcase.TAYLOR, "--out", tools.work / "bogus", "--partitioner", "bogus"], expect_ok=False)
rkcase.check(p.returncode != 0 and "--partitioner: bogus not in {metis-kway,metis-recursive}" in p.stderr,
             f"rkprep --partitioner bogus (1 rank): {p.stderr.strip()}")
# rkpost on a case whose files were cut or emptied: one error naming the file (and the line), no
# "internal error" (they read "stod" and a raw JSON parse error)
from shutil import copytree  # noqa: E402
cut = tools.case("upsetting_cut")
copytree(upset, cut)
rows = (cut / "history.csv").read_text().splitlines()
bad = "0.0006,1e-07,0.00" + rows[5][rows[5].index(",", 20):].replace(",", ",x", 1)
(cut / "history.csv").write_text("\n".join(rows[:5] + [bad] + rows[6:8]) + "\n")
# the same row as the file's last (cut by a full disk, or read while rksolve writes): left out, with a warning
(cut / "history.csv").write_text("\n".join(rows[:5] + [bad]) + "\n")
p = tools.post(cut)
rkcase.check("rkpost: warning: " in p.stderr and "history.csv:6: column " in p.stderr and "the row is left out" in p.stderr,
             f"rkpost, the last history row cut: {p.stderr.strip()[:200]}")
(cut / "history.csv").write_text("\n".join(rows[:5] + [bad] + rows[6:8]) + "\n")
for damage, says in (("history", f"{cut / 'history.csv'}:6: column "), ("prep", f"{cut / 'prep.json'}: not rkprep's JSON")):
    if damage == "prep":
        (cut / "prep.json").write_text("")
    p = tools.post(cut, expect_ok=False)
    rkcase.check(p.returncode != 0 and says in p.stderr and "internal error" not in p.stderr, f"rkpost, {damage} damaged: {p.stderr.strip()}")
if not scripts_too:  # the rest of this file checks the scripts
    raise SystemExit(0)

# The scripts that read a case. --help, and one message (no traceback) for a folder that is not a case
# or a case of another scene
SCRIPTS = ("taylor_metrics", "plot_taylor", "upsetting_check", "history_plots", "forming_report", "beam_check",
           "elastic_bar_check", "pressure_oscillation")
for name in SCRIPTS:
    script = rkcase.ROOT / "scripts" / f"{name}.py"
    p = tools.run(["/usr/bin/python3", script, "--help"], expect_ok=False)
    rkcase.check(p.returncode == 0 and "usage:" in p.stdout, f"{name}.py --help")
    p = tools.run(["/usr/bin/python3", script, tools.work / "not_a_case"], expect_ok=False)
    rkcase.check(p.returncode != 0 and "Traceback" not in p.stderr and "not a case folder" in p.stderr,
                 f"{name}.py on a non-case: {p.stderr.strip().splitlines()[-1]}")
p = tools.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / "upsetting_check.py", case], expect_ok=False)
rkcase.check(p.returncode != 0 and "expects a case of the upsetting" in p.stderr and "taylor_bar.geo" in p.stderr,
             f"upsetting_check.py on a Taylor bar: {p.stderr.strip()}")
# the upsetting is not a Taylor bar: one message and no traceback; upsetting_check calls the force's
# departure from the frictionless closed form a difference, not an error
p = tools.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / "taylor_metrics.py", upset], expect_ok=False)
rkcase.check(p.returncode != 0 and "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1
             and "expects a case of the Taylor bar" in p.stderr and "billet.geo" in p.stderr,
             f"taylor_metrics.py on an upsetting case: {p.stderr.strip()}")
p = tools.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / "upsetting_check.py", upset])
table = [ln for ln in p.stdout.splitlines() if ln.startswith("reduction")]
rkcase.check(table == ["reduction  force (kN)  exact (kN)  difference"] and "   10 %" in p.stdout
             and "friction mu = 0.12: the differences below are from the frictionless closed form, not errors" in p.stdout,
             f"upsetting_check.py with friction: the force's departure is a difference: {p.stdout.strip()}")

# solve.json of another format (a run of another rksolve version; history.csv has no format of its
# own, the solve.json of its run vouches for it): every script that reads the case refuses it with
# one line naming the file, exit 1, no traceback; a damaged one the same; a run that did not finish
# (no solve.json) is read as it is. The scripts read the format rksolve writes (shared/run_summary.hpp).
import json  # noqa: E402
import re  # noqa: E402
import shutil  # noqa: E402
import case_check  # noqa: E402
cpp = re.search(r"kRunSummaryFormat = (\d+);", (rkcase.ROOT / "shared" / "run_summary.hpp").read_text())
rkcase.check(cpp and int(cpp[1]) == case_check.SOLVE_FORMAT,
             f"the scripts read solve.json format {case_check.SOLVE_FORMAT}, rksolve writes {cpp and cpp[1]}")
other = tools.case("solve_format_7")
shutil.copytree(upset, other)
summary = json.loads((other / "solve.json").read_text())
for content, says in ((json.dumps({**summary, "format": 7}), "written by another version of rksolve (format 7, this "
                       f"script reads {case_check.SOLVE_FORMAT}); re-run rksolve on the case"),
                      ('{"format": 1, "steps":', "cannot read it as JSON")):
    (other / "solve.json").write_text(content)
    for name in SCRIPTS:
        p = tools.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / f"{name}.py", other], expect_ok=False)
        lines = p.stderr.strip().splitlines()
        rkcase.check(p.returncode == 1 and len(lines) == 1 and lines[0].startswith(f"{name}.py: {other / 'solve.json'}: {says}"),
                     f"{name}.py: {p.stderr.strip()}")
(other / "solve.json").unlink()
p = tools.run(["/usr/bin/python3", rkcase.ROOT / "scripts" / "upsetting_check.py", other])
rkcase.check("   10 %" in p.stdout, "upsetting_check.py reads a run without solve.json (one that did not finish)")
