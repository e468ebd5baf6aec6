#!/usr/bin/python3
"""Heat conduction in a bar with both ends held at T1 (geometry/heat_slab): the particles' temperature
in every frame after t = 0 against the series solution of the slab (Carslaw & Jaeger, Conduction of
Heat in Solids, 1959, section 3.3), T(x, t) = T1 + (T0 - T1) sum_{n odd} 4 / (n pi) sin(n pi x / L)
exp(-n^2 pi^2 alpha t / L^2), alpha = k / (rho c), and, with --convection H, the bar whose ends lose
heat to air at T1 through a film of conductance H (section 3.11): the series over the roots of
beta tan(beta) = Bi with Bi = H L / (2 k). Frames are read with meshio, independently of the solver.
The error is the largest |T - T_exact| over the particles (T^h(X_I), as rkpost writes it), as a
fraction of |T1 - T0|. Usage:
  heat_slab_check.py CASE [--convection H] [--json]
"""
import argparse
import json
import math
import re
from pathlib import Path

import meshio
import numpy as np
import yaml

from case_check import case_folder, require_part


def fixed_ends(x, t, L, alpha, T0, T1, terms=400):
    s = np.zeros_like(x)
    for n in range(1, 2 * terms, 2):
        s += 4 / (n * math.pi) * np.sin(n * math.pi * x / L) * math.exp(-(n * math.pi / L) ** 2 * alpha * t)
    return T1 + (T0 - T1) * s


def convective_ends(x, t, L, alpha, k, H, T0, T1, terms=200):
    """Symmetric about the bar's middle: the half-slab -l..l, l = L / 2, with a film on both faces."""
    l, bi = L / 2, H * L / (2 * k)
    s = np.zeros_like(x)
    for j in range(terms):  # the j-th root of beta tan(beta) = Bi lies in (j pi, j pi + pi / 2)
        lo, hi = j * math.pi + 1e-12, j * math.pi + math.pi / 2 - 1e-12
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if mid * math.tan(mid) < bi else (lo, mid)
        b = 0.5 * (lo + hi)
        c = 2 * math.sin(b) / (b + math.sin(b) * math.cos(b))
        s += c * np.cos(b * (x - l) / l) * math.exp(-b * b * alpha * t / (l * l))
    return T1 + (T0 - T1) * s


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", type=case_folder(("vtk/case.pvd",)))
    p.add_argument("--convection", type=float, default=None, help="the ends' film conductance H (W/m^2 K)")
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    require_part(a.case, ("slab.geo",), "heat slab (geometry/heat_slab)")
    scene = yaml.safe_load((a.case / "scene.resolved.yaml").read_text())
    mat = scene["material"]
    k, rho, c = mat["conductivity"], mat["density"], mat["specific_heat"]
    T0 = scene["initial_conditions"]["temperature"]
    alpha, L = k / (rho * c), 0.02
    faces = scene["thermal"]["fixed_faces"]
    if (a.convection is None) != bool(faces):
        raise SystemExit(f"heat_slab_check.py: {a.case}: give --convection exactly when the ends are not held at a temperature")
    T1 = faces[0]["temperature"] if faces else scene["thermal"]["ambient_temperature"]
    pvd = (a.case / "vtk/case.pvd").read_text()
    frames = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd)
    out = {"alpha_m2_s": alpha, "frames": []}
    for t, name in frames:
        t = float(t)
        if t <= 0:
            continue
        m = meshio.read(a.case / "vtk" / name)
        x, T = m.points[:, 0], m.point_data["temperature"].reshape(-1)
        exact = fixed_ends(x, t, L, alpha, T0, T1) if faces else convective_ends(x, t, L, alpha, k, a.convection, T0, T1)
        error = float(np.max(np.abs(T - exact)) / abs(T1 - T0))
        out["frames"].append({"time_s": t, "max_error": error, "mean_K": float(np.mean(T)),
                              "exact_mean_K": float(np.mean(exact))})
    out["max_error"] = max(f["max_error"] for f in out["frames"])
    if a.json:
        print(json.dumps(out, indent=1))
    else:
        print(" ".join(f"t={f['time_s']:g}s err={f['max_error']:.4f}" for f in out["frames"]),
              f"max {out['max_error']:.4f}")


if __name__ == "__main__":
    main()
