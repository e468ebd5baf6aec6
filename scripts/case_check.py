"""The command line the case checks share (beam_check.py, elastic_bar_check.py): CASE [--json],
the check's numbers as JSON or as the check's one-line summary."""
import argparse
import json
import sys
from pathlib import Path


def main_of(doc: str, check, summary) -> None:
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("case", type=Path)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    r = check(a.case)
    print(json.dumps(r, indent=2) if a.json else summary(r))
    sys.exit(0)
