#!/usr/bin/python3
"""The studies: which cases each one runs, how one case is prepared and solved, and the report.

Driven by studies/Makefile (`make -C studies <name>`); by hand:
  studies.py plan STUDY          write work/STUDY.mk (the case list and its prep dependencies)
  studies.py prep KEY            rkprep one prepared discretization (shared by the cases that use it)
  studies.py solve STUDY/CASE    rksolve (+ rkpost) one case, in its own folder
  studies.py report STUDY        results/STUDY/{cases.csv, table.md, *.png}
  studies.py adopt STUDY/CASE DIR [NOTE]  record a case solved elsewhere (its case folder) as if solved here
  studies.py remeasure STUDY/CASE  measure a finished case again (after a metric changed)
SMOKE=1 in the environment selects each study's two-point smoke version (tiny cases; `make test`).
TAYLOR_H="0.9 0.6 0.45", UPSET_H="2.5 2 1.25" narrow the convergence series (spacings in mm).
"""
import csv
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "scripts"))
import beam_check  # noqa: E402
import case_check  # noqa: E402
import taylor_metrics  # noqa: E402
import upsetting_check  # noqa: E402
from history_plots import pyplot  # noqa: E402

SMOKE = os.environ.get("SMOKE", "0") == "1"
DRIFT_END = float(os.environ.get("DRIFT_END", "0.1"))  # s; 1.09e6 steps of the stability study's bar at CFL 0.9
OUT = Path(os.environ.get("STUDIES_OUT", HERE))  # where work/ and results/ go (tests: the build tree)
WORK = OUT / ("work-smoke" if SMOKE else "work")
RESULTS = OUT / ("results-smoke" if SMOKE else "results")
BIN = Path(os.environ.get("BIN", ROOT / "build" / "bin"))
TAYLOR = "taylor_bar/scene.yaml"  # scenes under geometry/
TAYLOR_ELASTIC = "taylor_bar/scene_elastic.yaml"
TAYLOR_JC = "taylor_bar/scene_johnson_cook.yaml"
UPSET = "upsetting/scene.yaml"
UPSET_FRICTION = "upsetting/scene_friction.yaml"
UPSET_HOT = "upsetting/scene_hot.yaml"
THIN_WALL = "thin_wall/scene.yaml"
BEAM = "beam/scene.yaml"
BAR_WALLS = "elastic_bar/scene_walls.yaml"
TAYLOR_WALL = "taylor_bar/scene_contact.yaml"  # the bar against a penalty rigid wall instead of the held face
# converged finite-element values at 80 us (Foulk et al. 2021): the reference for the errors
TAYLOR_REF = {"footprint_radius_mm": 7.22, "final_length_mm": 21.45}
PAPER_SPEEDUP = {2: 1.81, 4: 3.21, 8: 6.41, 16: 10.39, 32: 24.14}  # Taylor bar, Table 2 of Wang et al. 2007
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1"}


class Case:
    """One run: a scene, the prep-side settings (they key the shared prep), the solver-side settings."""

    def __init__(self, name, scene, prep=(), solve=(), ranks=1, label=None, **tags):
        self.name, self.scene, self.prep, self.solve, self.ranks = name, scene, list(prep), list(solve), ranks
        self.label = label or name
        self.tags = tags

    @property
    def prep_key(self):
        text = json.dumps([self.scene, sorted(self.prep), self.ranks])
        slug = "-".join([Path(self.scene).parent.name, *(s.split("=")[0].split(".")[-1] + s.split("=")[1] for s in sorted(self.prep)), f"r{self.ranks}"])
        return slug.replace("=", "").replace("/", "_")[:60] + "-" + hashlib.sha1(text.encode()).hexdigest()[:8]


def taylor(h_mm, end_us, *solve, ranks=1, prep=(), scene=TAYLOR, **tags):
    return dict(scene=scene, prep=[f"discretization.spacing={h_mm}e-3", *prep],
                solve=[f"time.end={end_us}e-6", f"time.output_interval={end_us / 4}e-6", *solve], ranks=ranks, **tags)


def upsetting(h_mm, *solve, prep=(), scene=UPSET, **tags):
    return dict(scene=scene, prep=[f"discretization.spacing={h_mm}e-3", *prep],
                solve=["time.mass_scaling_dt=3e-7", "time.output_interval=1e-3", *solve], **tags)


def spacings(variable, default):
    """Spacings (mm) of a convergence series; the environment variable narrows it on a small machine."""
    text = os.environ.get(variable)
    return [float(h) for h in text.split()] if text else default


def convergence():
    hs, end = ([1.6, 1.2], 20) if SMOKE else (spacings("TAYLOR_H", [0.9, 0.6, 0.45, 0.3, 0.25, 0.185]), 80)
    # the fine bars (31k and 111k particles, hours on one core) run on 2 ranks and checkpoint every
    # 10 minutes of wall time, so RESUME=1 continues one that was stopped
    # the third series is the default discretization on the stable step from the highest frequency
    # (time.stable_step), 2.7x fewer steps: what makes the finest level affordable on a small machine;
    # the fourth one Gauss point per cell (the fast setting: 8x fewer points than the default); the fifth
    # and sixth the hexahedra's four- and six-point rules (discretization.cell_rule; not in the smoke run)
    series = [("gauss", "", [], []), ("nodal", "_nodal", ["discretization.integration=nodal"], []),
              ("frequency", "_frequency", [], ["time.stable_step=frequency"]),
              ("gauss1", "_gauss1", ["discretization.gauss_order=1"], [])]
    if not SMOKE:
        series += [(rule, f"_{rule}", [f"discretization.cell_rule={rule}"], []) for rule in ("four_point", "six_point")]
    cases = [Case(f"taylor{tag}_h{h}", **taylor(h, end, *solve, *(["output.checkpoint_minutes=10"] if h < 0.4 else []),
                                                 prep=prep, ranks=2 if h < 0.4 else 1), h=h, series=name)
             for name, tag, prep, solve in series for h in hs]
    for h in ([3.0, 2.5] if SMOKE else spacings("UPSET_H", [2.5, 2.0, 1.25, 0.8])):
        solve = ["time.end=1.1e-3", "time.output_interval=1.1e-3"] if SMOKE else []
        cases.append(Case(f"upsetting_h{h}", **upsetting(h, *solve), h=h))
    if not SMOKE:  # one Gauss point per cell on a forming case: what its hourglass modes do to the force
        cases.append(Case("upsetting_gauss1_h1.25", **upsetting(1.25, prep=["discretization.gauss_order=1"]), h=1.25,
                          series="gauss1"))
    return cases


def tradeoffs():
    h, end = (1.6, 20) if SMOKE else (0.9, 80)
    knobs = [("default", [], [])]
    if SMOKE:
        knobs += [("cfl 0.25", [], ["time.cfl=0.25"])]
    else:
        knobs += [(f"dilation {a}", [f"discretization.dilation={a}"], []) for a in (1.5, 2.5, 3.0)]
        knobs += [("kernel quartic", ["discretization.kernel=quartic_spline"], []),
                  ("basis quadratic", ["discretization.basis=quadratic", "discretization.dilation=3.0"], []),
                  ("gauss 1", ["discretization.gauss_order=1"], []), ("gauss 3", ["discretization.gauss_order=3"], []),
                  ("four point rule", ["discretization.cell_rule=four_point"], []),
                  ("six point rule", ["discretization.cell_rule=six_point"], []),
                  ("no F-bar", ["discretization.volumetric=none"], []),
                  ("nodal integration", ["discretization.integration=nodal"], []),
                  ("ebc transformation", ["discretization.ebc_method=transformation"], [])]
        knobs += [(f"cfl {c}", [], [f"time.cfl={c}"]) for c in (0.1, 0.25, 0.5, 0.75)]
        # the stable step from the highest frequency (time.stable_step), at 0.9 and 0.6 of its limit
        knobs += [(f"frequency step cfl {c}", [], ["time.stable_step=frequency", f"time.cfl={c}"]) for c in (0.9, 0.6)]
    cases = [Case("taylor_" + k.replace(" ", "_"), **taylor(h, end, *s, prep=p), label=k) for k, p, s in knobs]
    for k in ([0.25] if SMOKE else [0.05, 0.1, 0.25, 0.5, 1.0]):
        solve = ["time.end=1.1e-3", "time.output_interval=1.1e-3"] if SMOKE else []
        cases.append(Case(f"upsetting_penalty{k}", **upsetting(3.0 if SMOKE else 2.0, f"contact.penalty_scale={k}",
                                                                *solve), label=f"penalty {k}"))
    if not SMOKE:
        cases.append(Case("upsetting_nodal_integration", **upsetting(2.0, prep=["discretization.integration=nodal"]),
                          label="upsetting nodal integration"))
    return cases


def stability():
    h, end = (1.6, 10) if SMOKE else (1.2, 40)
    knobs = [("jitter 0.4", ["discretization.jitter=0.4"], []), ("cfl 2.0", [], ["time.cfl=2.0"])] if SMOKE else [
        *[(f"cfl {c}", [], [f"time.cfl={c}"]) for c in (0.9, 1.0, 1.2, 1.5, 2.0)],
        *[(f"dilation {a}", [f"discretization.dilation={a}"], []) for a in (1.5, 1.2, 1.0)],
        *[(f"jitter {j}", [f"discretization.jitter={j}"], []) for j in (0.1, 0.2, 0.4)],
        *[(f"nu {nu}", [], [f"material.poisson_ratio={nu}"]) for nu in (0.45, 0.49, 0.499)],
        *[(f"{v} m/s", [], [f"initial_conditions.velocity=[0,0,-{v}]"]) for v in (10, 100, 500, 1000)],
        # nodal integration (one point per particle) at the extremes of the same table
        ("nodal cfl 1.5", ["discretization.integration=nodal"], ["time.cfl=1.5"]),
        ("nodal jitter 0.4", ["discretization.integration=nodal", "discretization.jitter=0.4"], []),
        ("nodal 500 m/s", ["discretization.integration=nodal"], ["initial_conditions.velocity=[0,0,-500]"]),
        # reference updates (every 0.2 of Green strain) at the same extremes
        *[(f"updates {k}", p, ["reference_updates.strain=0.2", *v]) for k, p, v in (
            ("cfl 2.0", [], ["time.cfl=2.0"]), ("jitter 0.4", ["discretization.jitter=0.4"], []),
            ("nu 0.499", [], ["material.poisson_ratio=0.499"]),
            *[(f"{v} m/s", [], [f"initial_conditions.velocity=[0,0,-{v}]"]) for v in (500, 1000)])],
        (f"elastic {DRIFT_END:g} s", [], ["initial_conditions.velocity=[1,0,0]", f"time.end={DRIFT_END}",
                                   "time.output_interval=1e-2", "output.checkpoint_steps=0"])]
    cases = [Case("taylor_" + k.replace(" ", "_").replace("/", ""),
                  **taylor(h, end, *s, prep=p, scene=TAYLOR_ELASTIC if "elastic" in k else TAYLOR), label=k)
             for k, p, s in knobs]
    if not SMOKE:
        # the bar against the penalty rigid wall, whose spring takes more of its limit above CFL 0.9
        cases += [Case(f"taylor_rigid_wall_cfl_{c}", **taylor(h, end, f"time.cfl={c}", scene=TAYLOR_WALL),
                       label=f"rigid wall cfl {c}") for c in (0.9, 1.5, 2.0)]
        # a thin feature: the wall's 1.2 mm thickness with 2 particles across, and with 3
        for across, h_wall in ((2, 1.2), (3, 0.6)):
            cases.append(Case(f"thin_wall_{across}_across", scene=THIN_WALL, prep=[f"discretization.spacing={h_wall}e-3"],
                              solve=["time.end=40e-6", "time.output_interval=10e-6"], label=f"thin wall, {across} across"))
        # a long elastic run: the clamped beam vibrating freely for about 10^5 steps (scripts/beam_check.py)
        for cfl in (0.9, 0.8, 0.65, 0.5):
            cases.append(Case(f"beam_cfl_{cfl}", scene=BEAM, solve=[f"time.cfl={cfl}", "output.checkpoint_steps=0"],
                              label=f"beam, 40 ms, cfl {cfl}"))
        # contact over a long run: the elastic bar bouncing between two walls, with and without bulk
        # viscosity (1.5 mm spacing: 2 ms, about 50 contacts, 2.6 x 10^4 steps)
        for name, sets in (("", []), ("_no_viscosity", ["bulk_viscosity.quadratic=0", "bulk_viscosity.linear=0"])):
            cases.append(Case(f"bar_between_walls{name}", scene=BAR_WALLS, prep=["discretization.spacing=1.5e-3"],
                              solve=sets, label="bar between walls, 2 ms" + name.replace("_", " ")))
    return cases


def features():
    h, end = (1.6, 10) if SMOKE else (0.9, 20)
    cases = [Case("taylor_j2", **taylor(h, end), label="J2 plasticity"),
             Case("taylor_elastic", **taylor(h, end, "initial_conditions.velocity=[0,0,-227]", scene=TAYLOR_ELASTIC),
                  label="elastic only")]
    if not SMOKE:
        cases.append(Case("taylor_exact_ebc", **taylor(h, end, prep=["discretization.ebc_method=transformation"]),
                          label="exact symmetry planes"))
        cases.append(Case("taylor_output_often", **taylor(h, end, f"time.output_interval={end / 100}e-6"),
                          label="output every 1 %"))
        # the cost of a temperature: Johnson-Cook heated adiabatically, then with conduction (copper's k)
        cases.append(Case("taylor_johnson_cook", **taylor(h, end, scene=TAYLOR_JC), label="Johnson-Cook, adiabatic"))
        cases.append(Case("taylor_johnson_cook_conduction", **taylor(h, end, "material.conductivity=390", scene=TAYLOR_JC),
                          label="Johnson-Cook with conduction"))
        for k, scene in (("frictionless", UPSET), ("friction 0.12", UPSET_FRICTION)):
            cases.append(Case("upsetting_" + k.replace(" ", "_").replace(".", ""),
                              **upsetting(2.0, "time.end=1.5e-3", "time.output_interval=1.5e-3", scene=scene), label=k))
        # hot forging: C45 (Hansel-Spittel), conduction with c(T) and k(T) tables, die chilling, shear friction
        cases.append(Case("upsetting_hot", scene=UPSET_HOT, prep=["discretization.spacing=2.5e-3"],
                          solve=["time.end=0.1", "time.output_interval=0.1"], label="hot, C45 with conduction, 0.1 s"))
        cases.append(Case("upsetting_mass_scaling_off", **upsetting(2.0, "time.mass_scaling_dt=0", "time.end=1.5e-3",
                                                                    "time.output_interval=1.5e-3"), label="no mass scaling"))
    return cases


def scaling():
    ranks = [int(r) for r in os.environ.get("RANKS", "1 2").split()]
    h, end = (1.6, 5) if SMOKE else (0.6, 20)
    return [Case(f"taylor_n{n}", **taylor(h, end, ranks=n), label=f"{n} ranks", n=n) for n in ranks]


STUDIES = {f.__name__: f for f in (convergence, tradeoffs, stability, features, scaling)}


def cases_of(study):
    return {c.name: c for c in STUDIES[study]()}


CASE_TIMEOUT = float(os.environ.get("CASE_TIMEOUT", "900"))  # s of wall time per run; longer is a verdict


def run(args, cwd=None, check=True, timeout=None):
    # own process group, so a run past its time limit is stopped with all of mpirun's ranks
    proc = subprocess.Popen([str(a) for a in args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd,
                            env=dict(os.environ, **MPI_ENV), start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        p = subprocess.CompletedProcess(args, proc.returncode, out, err)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return subprocess.CompletedProcess(args, 124, "", f"error: exceeded the study's CASE_TIMEOUT = {timeout:g} s "
                                                        "of wall time (the stable step kept falling)")
    if check and p.returncode != 0:
        sys.exit(f"{' '.join(map(str, args))} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p


def plan(study):
    lines = []
    targets = []
    preps = set()
    for c in STUDIES[study]():
        target = f"$(WORK)/{study}/{c.name}/case.json"
        targets.append(target)
        # a case is redone when its prep or the solver changed; a prep when rkprep or the scene's
        # folder (scene, CAD) changed, so no case runs on files of an older scene layout
        lines.append(f"{target}: $(WORK)/prep/{c.prep_key}/prep.json $(BIN)/rksolve $(BIN)/rkpost")
        if c.prep_key not in preps:
            preps.add(c.prep_key)
            inputs = " ".join(sorted(str(f) for f in (ROOT / "geometry" / c.scene).parent.iterdir() if f.is_file()))
            lines.append(f"$(WORK)/prep/{c.prep_key}/prep.json: $(BIN)/rkprep {inputs}")
    WORK.mkdir(parents=True, exist_ok=True)
    text = f"{study}_CASES := {' '.join(targets)}\n" + "\n".join(lines) + "\n"
    path = WORK / f"{study}.mk"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def find_case_by_prep_key(key):
    for study in STUDIES:
        for c in STUDIES[study]():
            if c.prep_key == key:
                return c
    sys.exit(f"no study case uses the prep {key}")


def prep(key):
    c = find_case_by_prep_key(key)
    out = WORK / "prep" / key
    shutil.rmtree(out, ignore_errors=True)
    args = [BIN / "rkprep", ROOT / "geometry" / c.scene, "--ranks", c.ranks, "--out", out, "--quiet"]
    for s in c.prep:
        args += ["--set", s]
    p = run(args, check=False)
    if p.returncode != 0:  # a refused discretization is a result too (stability: dilation below the minimum)
        out.mkdir(parents=True, exist_ok=True)
        (out / "refused.txt").write_text(p.stderr.strip() or p.stdout.strip())
        (out / "prep.json").write_text(json.dumps({"refused": True}))


def solve(name):
    study, case_name = name.split("/")
    c = cases_of(study)[case_name]
    prep_dir = WORK / "prep" / c.prep_key
    out = WORK / study / c.name
    resume = os.environ.get("RESUME") == "1" and (out / "checkpoint").is_dir()  # go on from its checkpoint
    if not resume:
        shutil.rmtree(out, ignore_errors=True)
        out.mkdir(parents=True)
    result = {"study": study, "case": c.name, "label": c.label, "ranks": c.ranks, **c.tags,
              "prep": c.prep, "solve": c.solve}
    if (prep_dir / "refused.txt").exists():
        said = [ln for ln in (prep_dir / "refused.txt").read_text().splitlines() if "error:" in ln]
        result.update(verdict="refused by rkprep", message=(said or ["(no message)"])[0])
    else:
        for f in ("sub", "scene.resolved.yaml", "prep.json"):
            if not resume:
                (out / f).symlink_to(prep_dir / f)
        args = ["mpirun", "-np", c.ranks, BIN / "rksolve", out, "--quiet", *(["--restart"] if resume else [])]
        for s in c.solve:
            args += ["--set", s]
        p = run(args, check=False, timeout=CASE_TIMEOUT)
        if p.returncode == 124:
            result.update(verdict="exceeded the time limit", message=p.stderr)
        elif p.returncode != 0:
            said = [ln for ln in (p.stderr + p.stdout).splitlines() if "error:" in ln] or [p.stderr.strip()[-300:]]
            result.update(verdict="stopped with a diagnostic", message=said[0])
        else:
            result["verdict"] = "completed"
        measure(c, out, result)
    (out / "case.json").write_text(json.dumps(result, indent=2))


def adopt(name, source, note=""):
    """A case solved elsewhere (a bigger machine, another rank count: the answer does not depend on it)
    from its case folder (sub/, results/, solve.json, ...): measured and recorded as if solved here."""
    study, case_name = name.split("/")
    c = cases_of(study)[case_name]
    out = WORK / study / c.name
    shutil.rmtree(out, ignore_errors=True)
    shutil.copytree(source, out, symlinks=True)
    s = case_check.read_solve(out)
    result = {"study": study, "case": c.name, "label": c.label, "ranks": s["ranks"], **c.tags, "prep": c.prep,
              "solve": c.solve, "verdict": "completed", "solved_elsewhere": note or str(source)}
    measure(c, out, result)
    (out / "case.json").write_text(json.dumps(result, indent=2))


def remeasure(name):
    """Measures a finished case again (after the metrics changed), keeping how it was run."""
    study, case_name = name.split("/")
    out = WORK / study / case_name
    result = json.loads((out / "case.json").read_text())
    measure(cases_of(study)[case_name], out, result)
    (out / "case.json").write_text(json.dumps(result, indent=2))


def measure(c, out, result):
    """solve.json's figures, rkpost, and the case's own metrics into result."""
    if (out / "solve.json").exists():
        s = case_check.read_solve(out)
        result.update({k: s[k] for k in ("wall_s", "setup_s", "steps", "particles", "integration_points",
                                         "ns_per_point_update", "energy_error", "peak_memory_mb_max_rank")})
    result["prep_s"] = json.loads((out / "prep.json").read_text()).get("wall_s")
    if (out / "results").exists():
        run([BIN / "rkpost", out, "--quiet", "--no-pictures"], check=False)
    if (out / "vtk" / "case.pvd").exists():
        if c.scene.startswith("taylor_bar/"):
            m = taylor_metrics.metrics(out)
            result.update(m)
            result["error"] = sum(abs(m[k] / v - 1) for k, v in TAYLOR_REF.items())
            if c.scene == TAYLOR:  # every frame against the converged history
                result.update(taylor_metrics.history_errors(out))
        elif c.scene == BEAM:  # long elastic runs: the frequency and the energy's drift
            result.update(beam_check.check(out))
        elif c.scene == BAR_WALLS:
            result.update(case_check.energy_drift(out))
        elif c.scene == THIN_WALL:  # no reference: whether it holds together, its height, its strain
            m = taylor_metrics.metrics(out)
            result.update({k: m[k] for k in ("finite", "final_length_mm", "max_eq_plastic_strain")})
        else:
            u = upsetting_check.check(out)
            result["force_errors"] = {f"{100 * f['reduction']:.0f}%": f["error"] for f in u["force"]}
            result["error"] = max(abs(f["error"]) for f in u["force"]) if u["force"] else None
            result["diameter_error"] = u["diameter_error"]
        if result["verdict"] == "completed" and not result.get("finite", True):
            result["verdict"] = "NON-FINITE OUTPUT"


def fmt(v, digits=4):
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{digits}g}"
    return str(v)


def kept_row(row, c):
    """A case's row of the previous cases.csv, as numbers again, with the case's tags (h, series)."""
    def value(v):
        for kind in (int, float):
            try:
                return kind(v)
            except ValueError:
                pass
        return v or None
    return {**{k: value(v) for k, v in row.items()}, **c.tags, "kept": True}


def report(study):
    out = RESULTS / study
    out.mkdir(parents=True, exist_ok=True)
    # work/ is not kept with the results: a case whose run is gone (a fresh checkout, a cleaned work/)
    # keeps its row of the previous cases.csv, and the table says which rows those are
    previous = {}
    if not SMOKE and (out / "cases.csv").exists():
        with open(out / "cases.csv", newline="") as f:
            previous = {r["case"]: r for r in csv.DictReader(f)}
    rows, pending = [], []  # pending: `studies.py report` by hand while cases run
    for c in STUDIES[study]():
        done = WORK / study / c.name / "case.json"
        if done.exists():
            rows.append(json.loads(done.read_text()))
        elif c.name in previous:
            rows.append(kept_row(previous[c.name], c))
        else:
            pending.append(c.name)
    keys = ["label", "verdict", "ranks", "particles", "steps", "wall_s", "ns_per_point_update", "energy_error",
            "footprint_radius_mm", "final_length_mm", "max_eq_plastic_strain", "error", "diameter_error", "message"]
    if study == "convergence":  # every frame against the converged history; the rim's radius at fixed heights
        keys[-1:-1] = ["footprint_radius_history_error", "final_length_history_error", "radius_0.1mm_mm",
                       "radius_0.2mm_mm", "max_radius_mm"]
    if study == "stability":  # the long runs: their largest energy error, the mechanical energy's drift, f1
        keys[-1:-1] = ["max_energy_error", "energy_end_over_start", "f1_error"]
    if study == "convergence":
        for r in rows:  # cases measured before the history was compared
            case = WORK / study / r["case"]
            if r["case"].startswith("taylor") and "final_length_history_error" not in r and (case / "vtk" / "case.pvd").exists():
                r.update(taylor_metrics.history_errors(case))
    with open(out / "cases.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case"] + keys)
        for r in rows:
            w.writerow([r["case"]] + [r.get(k) for k in keys])
    shown = [k for k in keys if k != "message" and any(r.get(k) is not None for r in rows)]
    md = [f"# {study}", "", f"Machine: {os.uname().nodename}, {os.cpu_count()} cores; "
          f"{'smoke version' if SMOKE else 'full study'}. Error: Taylor bar = |r_f/7.22 - 1| + |L_f/21.45 - 1| "
          "(converged FE); *_history_error = largest |value(t) / converged FE history(t) - 1| over the frames; "
          "upsetting = largest |force error| against the closed form at 10-50 % reduction.", "",
          "| case | " + " | ".join(shown) + " |", "|---|" + "---|" * len(shown)]
    for r in rows:
        md.append(f"| {r['case']} | " + " | ".join(fmt(r.get(k)) for k in shown) + " |")
    notes = [r for r in rows if r.get("message")]
    if notes:
        md += ["", "Diagnostics (the message each stopped or refused run gave):", ""]
        md += [f"- {r['label']}: `{r['message'][:400]}`" for r in notes]
    kept = [r["case"] for r in rows if r.get("kept")]
    if kept:
        md += ["", f"Kept from the previous report (their runs were not in work/ when this one was written): "
               f"{', '.join(kept)}."]
    if pending:
        md += ["", f"Not finished when this report was written: {', '.join(pending)}."]
    elsewhere = [r for r in rows if r.get("solved_elsewhere")]
    if elsewhere:  # studies.py adopt: wall times from another machine or rank count
        md += ["", "Solved elsewhere (the answer does not depend on the rank count; the wall time is that machine's):", ""]
        md += [f"- {r['case']}: {r['solved_elsewhere']}" for r in elsewhere]
    extra = globals().get(f"report_{study}")
    if extra:
        md += extra(rows, out)
    (out / "table.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))


def observed_order(rows, key):
    """p from three successive resolutions h1 > h2 > h3 of f = f* + C h^p: (f1 - f2) / (f2 - f3) = (h1^p - h2^p) /
    (h2^p - h3^p), solved for p by bisection (the ratios of h need not be equal); "oscillates" where the two
    differences have opposite signs (no order), "-" where no p in (0.01, 20) fits."""
    out = []
    for a, b, c in zip(rows, rows[1:], rows[2:]):
        if None in (a.get(key), b.get(key), c.get(key)):
            continue
        d1, d2 = a[key] - b[key], b[key] - c[key]
        if d1 * d2 <= 0:
            out.append(f"{b['h']}: oscillates" if d1 * d2 < 0 else f"{b['h']}: -")
            continue
        fit = lambda q: (a["h"] ** q - b["h"] ** q) / (b["h"] ** q - c["h"] ** q) - d1 / d2  # rises with q
        lo, hi = 0.01, 20.0
        if fit(lo) * fit(hi) > 0:
            out.append(f"{b['h']}: -")
            continue
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if fit(mid) > 0 else (mid, hi)
        out.append(f"{b['h']}: {0.5 * (lo + hi):.2f}")
    return out


MARKS = {"gauss": "o-", "nodal": "^--", "frequency": "s:", "gauss1": "d-.", "four_point": "v-", "six_point": "x--"}  # the convergence series' lines


def report_convergence(rows, out):
    tay = [r for r in rows if r["case"].startswith("taylor") and r.get("footprint_radius_mm")]
    series = {name: [r for r in tay if r.get("series", "gauss") == name] for name in MARKS}
    ups = [r for r in rows if r["case"].startswith("upsetting") and r.get("error") is not None and "series" not in r]
    plt = pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for name, rs in series.items():
        for key, ref in (*TAYLOR_REF.items(), ("radius_0.2mm_mm", TAYLOR_REF["footprint_radius_mm"])):
            if rs and all(key in r for r in rs):
                ax[0].loglog([r["h"] for r in rs], [abs(r[key] / ref - 1) + 1e-6 for r in rs],
                             MARKS[name], label=f"{key} ({name})")
    if ups:
        ax[0].loglog([r["h"] for r in ups], [r["error"] for r in ups], "s-", label="upsetting force (max error)")
    ax[0].set_xlabel("spacing h (mm)")
    ax[0].set_ylabel("relative error")
    ax[0].legend(fontsize=7)
    for name, rs in series.items():
        if rs:
            ax[1].loglog([r["particles"] for r in rs], [r["wall_s"] * r["ranks"] for r in rs], MARKS[name],
                         label=f"Taylor bar, {name}: wall time x ranks")
    ax[1].set_xlabel("particles")
    ax[1].set_ylabel("wall time (s)")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=120)
    plt.close(fig)
    lines = ["", "![convergence](convergence.png)", ""]
    for name, rs in series.items():
        for key in (*TAYLOR_REF, "radius_0.2mm_mm"):
            lines.append(f"Observed order of {key}, {name} series (at h, from three successive h): "
                         f"{', '.join(observed_order(rs, key)) or '-'}")
    return lines


def pareto(points):
    """Indices of the points no other point beats in both error and time."""
    front = []
    for i, (e, t) in enumerate(points):
        if not any((e2 <= e and t2 <= t) and (e2 < e or t2 < t) for j, (e2, t2) in enumerate(points) if j != i):
            front.append(i)
    return sorted(front, key=lambda i: points[i][1])


FAST_ERROR = 0.05  # the "fast" pick: the quickest setting whose error stays within 5 %


def report_tradeoffs(rows, out):
    tay = [r for r in rows if r["case"].startswith("taylor") and r.get("error") is not None and r.get("wall_s")]
    lines = []
    if not tay:
        return lines
    pts = [(r["error"], r["wall_s"]) for r in tay]
    front = pareto(pts)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.scatter([p[1] for p in pts], [p[0] for p in pts], color="0.6")
    for r in tay:
        ax.annotate(r["label"], (r["wall_s"], r["error"]), fontsize=7)
    ax.plot([pts[i][1] for i in front], [pts[i][0] for i in front], "r-o", label="Pareto front")
    # fast: the quickest point of the front within FAST_ERROR (an engineering tolerance on the
    # footprint radius and length); accurate: the smallest error; balanced: the smallest error x time
    usable = [i for i in front if pts[i][0] <= FAST_ERROR] or front
    picks = {"fast": usable[0], "accurate": min(front, key=lambda i: pts[i][0])}
    picks["balanced"] = min(usable, key=lambda i: (pts[i][0] / max(p[0] for p in pts) + 1e-9) *
                            (pts[i][1] / max(p[1] for p in pts)))
    for k, (name, i) in enumerate(picks.items()):  # staggered, so picks close together stay readable
        ax.annotate(name, (pts[i][1], pts[i][0]), xytext=(10, 10 + 14 * k), textcoords="offset points", color="red",
                    arrowprops={"arrowstyle": "->", "color": "red"})
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("error (Taylor bar, vs converged FE)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "pareto.png", dpi=120)
    plt.close(fig)
    lines += ["", "![pareto](pareto.png)", "",
              f"Picks on the Pareto front: fast = the quickest with error <= {FAST_ERROR:g}, accurate = the smallest "
              "error, balanced = the smallest error x time.", "",
              "| pick | settings | error | wall time (s) |", "|---|---|---|---|"]
    for name, i in picks.items():
        lines.append(f"| {name} | {tay[i]['label']} | {tay[i]['error']:.4f} | {tay[i]['wall_s']:.1f} |")
    return lines


def report_scaling(rows, out):
    ok = [r for r in rows if r.get("wall_s")]
    if not ok:
        return []
    base = next((r for r in ok if r["ranks"] == 1), ok[0])
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    ns = [r["ranks"] for r in ok]
    ax.plot(ns, [base["wall_s"] / r["wall_s"] for r in ok], "o-", label="rkforge (this machine)")
    ax.plot([1, *PAPER_SPEEDUP], [1, *PAPER_SPEEDUP.values()], "s--", label="Wang et al. 2007, Taylor bar")
    ax.plot([1, max(ns + [32])], [1, max(ns + [32])], "k:", label="ideal")
    ax.set_xlabel("ranks")
    ax.set_ylabel("speedup")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "scaling.png", dpi=120)
    plt.close(fig)
    lines = ["", "![scaling](scaling.png)", "", "| ranks | wall (s) | speedup | efficiency | 2007 paper's speedup |",
             "|---|---|---|---|---|"]
    for r in ok:
        sp = base["wall_s"] / r["wall_s"]
        lines.append(f"| {r['ranks']} | {r['wall_s']:.2f} | {sp:.2f} | {100 * sp / r['ranks']:.0f} % | "
                     f"{PAPER_SPEEDUP.get(r['ranks'], '-')} |")
    return lines


if __name__ == "__main__":
    if sys.argv[1:2] == ["adopt"] and len(sys.argv) in (4, 5):
        adopt(sys.argv[2], Path(sys.argv[3]).resolve(), *sys.argv[4:])
    elif len(sys.argv) != 3 or sys.argv[1] not in ("plan", "prep", "solve", "report", "remeasure"):
        sys.exit(__doc__)
    else:
        {"plan": plan, "prep": prep, "solve": solve, "report": report, "remeasure": remeasure}[sys.argv[1]](sys.argv[2])
