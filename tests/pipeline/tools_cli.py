"""Each program on its own: --help and --version, and a clear error with a non-zero exit on bad use."""
import rkcase

tools = rkcase.tools_from_argv()
for prog in ("rkprep", "rksolve", "rkpost"):
    p = tools.run([tools.bin / prog, "--help"])
    wants = [prog, "--quiet"] + (["--set"] if prog != "rkpost" else [])
    rkcase.check(all(w in p.stdout for w in wants), f"{prog} --help names {', '.join(wants)}")
    p = tools.run([tools.bin / prog, "--version"])
    rkcase.check(p.stdout.startswith(f"{prog} (rkforge)"), f"{prog} --version: {p.stdout.strip()}")

p = tools.run([tools.bin / "rkprep", tools.work / "nope.yaml", "--out", tools.work / "x"], expect_ok=False)
rkcase.check(p.returncode != 0 and "nope.yaml: cannot open the scene file" in p.stderr, "rkprep: missing scene")
p = tools.run([tools.bin / "rkpost", tools.work / "not_a_case"], expect_ok=False)
rkcase.check(p.returncode != 0 and "prep.json: not found" in p.stderr, "rkpost: not a case directory")
case = tools.case("cli_bad_set")
tools.prep(case, 1, sets=["discretization.spacing=1.5e-3"])
p = tools.solve(case, 1, sets=["discretization.dilation=3"], expect_ok=False)
rkcase.check(p.returncode != 0 and "re-run rkprep" in p.stderr, "rksolve refuses a prep-side --set")
p = tools.solve(case, 1, sets=["time.cfl=abc"], expect_ok=False)
rkcase.check(p.returncode != 0 and "'time.cfl' must be a number" in p.stderr, "rksolve: bad --set value")
