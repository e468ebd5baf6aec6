"""What the case scripts share: a CASE argument that must be a case folder of the expected scene (one
clear message otherwise, never a traceback), solve.json read only in the format these scripts know,
the checks' command line CASE [--json] (the numbers as JSON or a one-line summary), and the energy
drift of a long run."""
import argparse
import csv
import json
import sys
from pathlib import Path

# The `format` of CASE/solve.json that these scripts read: rksolve's kRunSummaryFormat
# (shared/run_summary.hpp). history.csv carries no format of its own; the solve.json of the same run
# vouches for it.
SOLVE_FORMAT = 1


def refuse(message: str) -> None:
    """One line on stderr, naming the script, and exit status 1."""
    raise SystemExit(f"{Path(sys.argv[0]).name}: {message}")


def read_solve(case: Path) -> dict:
    """CASE/solve.json; refused with one line when it is damaged or of another format than SOLVE_FORMAT."""
    path = Path(case) / "solve.json"
    try:
        summary = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, ValueError) as e:
        refuse(f"{path}: cannot read it as JSON ({e.__class__.__name__}); re-run rksolve on the case")
    if not isinstance(summary, dict):
        refuse(f"{path}: not a JSON object (a damaged file?); re-run rksolve on the case")
    found = summary.get("format", 0)
    if found != SOLVE_FORMAT:
        refuse(f"{path}: written by another version of rksolve (format {found}, this script reads {SOLVE_FORMAT}); "
               "re-run rksolve on the case")
    return summary


def check_run(case: Path) -> None:
    """A finished run (one with solve.json) of the format these scripts read, else refused; a run that
    did not finish has no solve.json and its history.csv is read as it is."""
    if (Path(case) / "solve.json").exists():
        read_solve(case)


def energy_drift(case: Path) -> dict:
    """A long run's energy from history.csv: the largest energy error, and the mechanical energy
    (kinetic + internal less the bulk viscosity's dissipated work) at the end over its value after
    the first row: a growing mode of the discretization shows as a rise, damping as a fall."""
    rows = list(csv.DictReader(open(case / "history.csv")))
    total = [float(r["kinetic"]) + float(r["internal"]) - float(r.get("viscous_work") or 0) for r in rows]
    return {"time_s": float(rows[-1]["time"]), "max_energy_error": max(float(r["energy_error"]) for r in rows),
            "energy_end_over_start": total[-1] / max(total[1], 1e-300)}


def case_folder(needs=("prep.json",)):
    """An argparse type: a case folder holding `needs` (what the script reads), named in the message."""
    def check(text: str) -> Path:
        case = Path(text)
        for f in needs:
            if not (case / f).exists():
                made_by = {"prep.json": "rkprep", "history.csv": "rksolve", "vtk/case.pvd": "rkpost"}.get(f, "rkprep")
                raise argparse.ArgumentTypeError(f"{text}: not a case folder with {f} (written by {made_by})")
        if "vtk/case.pvd" in needs and any((case / "vtk").glob("frame_*.pvtu")) and not any((case / "vtk").glob("frame_*.vtu")):
            raise argparse.ArgumentTypeError(f"{text}: its frames are one piece per rank (rkpost --partitioned); this script "
                                             f"reads merged frames: run rkpost {text}")
        check_run(case)
        return case
    return check


def require_part(case: Path, parts, what: str) -> str:
    """Exits with one message unless the case's part (geometry.cad of scene.resolved.yaml) is one of `parts`;
    returns the part's file name."""
    text = (case / "scene.resolved.yaml").read_text() if (case / "scene.resolved.yaml").exists() else ""
    cad = next((ln.split(":", 1)[1].strip() for ln in text.splitlines() if ln.strip().startswith("cad:")), "?")
    if Path(cad).name not in parts:
        raise SystemExit(f"{Path(sys.argv[0]).name}: {case}: expects a case of the {what}; this one's part is {Path(cad).name}")
    return Path(cad).name


def main_of(doc: str, check, summary, needs=("history.csv",), parts=None, what="") -> None:
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("case", type=case_folder(needs))
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    if parts:
        require_part(a.case, parts, what)
    r = check(a.case)
    print(json.dumps(r, indent=2) if a.json else summary(r))
    sys.exit(0)
