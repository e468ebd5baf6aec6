#!/usr/bin/python3
"""Frictionless upsetting of an aluminium cylinder (geometry/upsetting) against the closed form.

F = sigma(ep) A0 H0 / H with ep = ln(H0/H) - sigma/E (aluminium of Table 4 of Wang et al. 2007), D = D0 sqrt(H0/H).
Reads CASE/history.csv (die force, full part) and the last .vtu (diameter, via meshio). The explicit
contact force rings with the stress waves, so each force is the mean of the history rows within
+-1 % reduction of the point, against the mean of the closed form over the same rows.
  upsetting_check.py CASE [--json]
"""
import argparse
import csv
import json
import math
from pathlib import Path

import meshio
import numpy as np

from case_check import case_folder, require_part

E, K, EPS0, N = 71e9, 576.79e6, 0.01658, 0.3593
D0 = H0 = 20e-3


def exact_force(reduction):
    H = H0 * (1 - reduction)
    sigma = 300e6
    for _ in range(200):
        sigma = K * (EPS0 + math.log(H0 / H) - sigma / E) ** N
    return sigma * math.pi * D0 ** 2 / 4 * H0 / H


def check(case: Path):
    rows = list(csv.DictReader(open(case / "history.csv")))
    half = H0 / 2  # one eighth is modeled: the die stroke is half the height reduction
    out = {"force": []}
    max_reduction = float(rows[-1]["die.stroke"]) / half
    for red in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7):
        if red > max_reduction + 1e-9:
            break
        near = [r for r in rows if abs(float(r["die.stroke"]) / half - red) <= 0.01 + 1e-9]
        # (at the end of the run the window is one-sided)
        f = np.mean([float(r["die.force"]) for r in near])
        exact = np.mean([exact_force(float(r["die.stroke"]) / half) for r in near])
        out["force"].append({"reduction": red, "force_kN": f / 1e3, "exact_kN": exact / 1e3, "error": f / exact - 1,
                             "rows": len(near)})
    vtu = sorted((case / "vtk").glob("frame_*.vtu"))[-1]
    x = meshio.read(vtu).points
    height = 2 * x[:, 2].max()
    diameter = 2 * np.hypot(x[:, 0], x[:, 1]).max()
    out["diameter_mm"] = 1e3 * diameter
    out["diameter_exact_mm"] = 1e3 * D0 * math.sqrt(H0 / height)
    out["diameter_error"] = diameter / (D0 * math.sqrt(H0 / height)) - 1
    out["max_energy_error"] = max(float(r["energy_error"]) for r in rows[len(rows) // 10:])  # after the start-up
    out["max_kinetic_internal_ratio"] = max(float(r["kinetic_internal_ratio"]) for r in rows[len(rows) // 10:])
    return out


def friction_of(case: Path) -> float:
    text = (case / "scene.resolved.yaml").read_text()
    return max((float(ln.split(":", 1)[1]) for ln in text.splitlines() if ln.strip().startswith("friction:")), default=0.0)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", type=case_folder(("prep.json", "history.csv", "vtk/case.pvd")))
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    require_part(a.case, ("billet.geo", "billet.step"), "upsetting (geometry/upsetting, upsetting_step)")
    res = check(a.case)
    if a.json:
        print(json.dumps(res, indent=2))
    else:
        mu = friction_of(a.case)
        if mu > 0:  # the closed form is frictionless: with friction the difference is the friction's share
            print(f"friction mu = {mu:g}: the differences below are from the frictionless closed form, not errors")
        print("reduction  force (kN)  exact (kN)  " + ("difference" if mu > 0 else "error"))
        for f in res["force"]:
            print(f"  {100 * f['reduction']:3.0f} %   {f['force_kN']:9.2f}  {f['exact_kN']:9.2f}  {100 * f['error']:+6.2f} %")
        print(f"diameter {res['diameter_mm']:.3f} mm, exact {res['diameter_exact_mm']:.3f} mm "
              f"({100 * res['diameter_error']:+.2f} %); energy error {100 * res['max_energy_error']:.2f} %, "
              f"max kinetic/internal {100 * res['max_kinetic_internal_ratio']:.2f} %")
