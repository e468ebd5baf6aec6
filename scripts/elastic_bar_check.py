#!/usr/bin/python3
"""The elastic bar onto a rigid wall (geometry/elastic_bar) from history.csv and prep.json: the
contact time (first to last history row with a wall force) against 2 L / c0, and the rebound speed
from the wall's impulse, v_out = integral F dt / M - v_in (M the modeled part's mass), against v_in
(an elastic bar on a rigid wall leaves at the speed it came); and the ringing of the contact stress
about rho c0 v on its plateau (5 us after the impact to 5 us before the wave's return: the RMS
deviation from rho c0 v A, a fraction of it). Usage:
  elastic_bar_check.py CASE [--json]
"""
import csv
import json
import math
from pathlib import Path

from case_check import main_of

L, E, RHO, V_IN = 0.1, 71.0e9, 2700.0, 5.0  # the scene's bar
C0 = math.sqrt(E / RHO)


def check(case: Path) -> dict:
    rows = list(csv.DictReader(open(case / "history.csv")))
    prep = json.loads((case / "prep.json").read_text())
    t = [float(r["time"]) for r in rows]
    f = [float(r["wall.force"]) for r in rows]
    on = [k for k, v in enumerate(f) if v > 0]
    impulse = sum(0.5 * (f[k] + f[k + 1]) * (t[k + 1] - t[k]) for k in range(len(t) - 1))
    mass = RHO * prep["volume_m3"]
    v_out = impulse / mass - V_IN
    contact = t[on[-1]] - t[on[0]] if on else 0.0
    section = prep["volume_m3"] / L  # the modeled section
    peak_stress = max(f) / section
    plateau = [f[k] / (RHO * C0 * V_IN * section) - 1 for k in range(len(t)) if on and 5e-6 < t[k] - t[on[0]] < 2 * L / C0 - 5e-6]
    ringing = math.sqrt(sum(d * d for d in plateau) / len(plateau)) if plateau else float("nan")
    return {"contact_time_s": contact, "contact_time_exact_s": 2 * L / C0, "contact_time_error": contact / (2 * L / C0) - 1,
            "rebound_speed_m_s": v_out, "rebound_error": v_out / V_IN - 1,
            "contact_stress_pa": peak_stress, "contact_stress_exact_pa": RHO * C0 * V_IN, "ringing": ringing,
            "still_in_contact": bool(f[-1] > 0), "max_energy_error": max(float(r["energy_error"]) for r in rows)}


def summary(r: dict) -> str:
    return (f"contact time {1e6 * r['contact_time_s']:.2f} us against 2L/c0 = {1e6 * r['contact_time_exact_s']:.2f} us "
            f"({100 * r['contact_time_error']:+.2f} %); rebound {r['rebound_speed_m_s']:.3f} m/s against {V_IN} "
            f"({100 * r['rebound_error']:+.2f} %); peak contact stress {r['contact_stress_pa'] / 1e6:.1f} MPa against "
            f"rho c0 v = {r['contact_stress_exact_pa'] / 1e6:.1f} MPa, ringing {100 * r['ringing']:.1f} % RMS; largest energy error {100 * r['max_energy_error']:.3f} %")


if __name__ == "__main__":
    main_of(__doc__, check, summary, parts=("elastic_bar.geo",), what="elastic bar (geometry/elastic_bar)")
