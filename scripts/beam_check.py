#!/usr/bin/python3
"""The clamped beam's free vibration (geometry/beam) from history.csv: the first bending frequency
from the kinetic energy, which peaks twice per period, against Euler-Bernoulli's clamped-free
f1 = (1.8751^2 / (2 pi L^2)) sqrt(E I / (rho A)), and the mechanical energy's drift over the run
(case_check.energy_drift). Usage:
  beam_check.py CASE [--json]
"""
import csv
import math
from pathlib import Path

from case_check import energy_drift, main_of, read_solve

L, B, E, RHO = 0.2, 0.01, 71.0e9, 2700.0  # the scene's beam
F1 = 1.8751 ** 2 / (2 * math.pi * L ** 2) * math.sqrt(E * B ** 4 / 12 / (RHO * B ** 2))


def check(case: Path) -> dict:
    rows = list(csv.DictReader(open(case / "history.csv")))
    t = [float(r["time"]) for r in rows]
    ke = [float(r["kinetic"]) for r in rows]
    # kinetic-energy peaks, from the first after a quarter period on (the start excites higher modes too)
    peaks = [t[k] for k in range(1, len(ke) - 1) if ke[k] > ke[k - 1] and ke[k] >= ke[k + 1] and ke[k] > 0.5 * max(ke)]
    periods = [b - a for a, b in zip(peaks, peaks[1:])]
    f = 1 / (2 * sum(periods) / len(periods)) if periods else float("nan")
    return {"steps": read_solve(case)["steps"] if (case / "solve.json").exists() else None,
            "f1_hz": f, "f1_beam_hz": F1, "f1_error": f / F1 - 1, "kinetic_peaks": len(peaks), **energy_drift(case)}


def summary(r: dict) -> str:
    return (f"beam to {1e3 * r['time_s']:.1f} ms ({r['steps']} steps): f1 {r['f1_hz']:.1f} Hz against {r['f1_beam_hz']:.1f} Hz "
            f"({100 * r['f1_error']:+.2f} %), largest energy error {100 * r['max_energy_error']:.3f} %, "
            f"energy end/start {r['energy_end_over_start']:.4f}")


if __name__ == "__main__":
    main_of(__doc__, check, summary, parts=("beam.geo",), what="clamped beam (geometry/beam)")
