"""What the case checks share (beam_check.py, elastic_bar_check.py): the command line CASE [--json],
the check's numbers as JSON or as the check's one-line summary; the energy drift of a long run."""
import argparse
import csv
import json
import sys
from pathlib import Path


def energy_drift(case: Path) -> dict:
    """A long run's energy from history.csv: the largest energy error, and the mechanical energy
    (kinetic + internal less the bulk viscosity's dissipated work) at the end over its value after
    the first row: a growing mode of the discretization shows as a rise, damping as a fall."""
    rows = list(csv.DictReader(open(case / "history.csv")))
    total = [float(r["kinetic"]) + float(r["internal"]) - float(r.get("viscous_work") or 0) for r in rows]
    return {"time_s": float(rows[-1]["time"]), "max_energy_error": max(float(r["energy_error"]) for r in rows),
            "energy_end_over_start": total[-1] / max(total[1], 1e-300)}


def main_of(doc: str, check, summary) -> None:
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("case", type=Path)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    r = check(a.case)
    print(json.dumps(r, indent=2) if a.json else summary(r))
    sys.exit(0)
