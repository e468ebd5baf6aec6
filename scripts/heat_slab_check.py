#!/usr/bin/python3
"""Heat conduction in the bar of geometry/heat_slab (20 x 4 x 4 mm, x along it), the particles'
temperature T^h(X_I) (as rkpost writes it) in every frame after t = 0 against the exact solution
(Carslaw & Jaeger, Conduction of Heat in Solids, 1959), alpha = k / (rho c):
- scene.yaml, both ends held at T1, the sides insulated (section 3.3):
  T = T1 + (T0 - T1) sum_{n odd} 4 / (n pi) sin(n pi x / L) exp(-n^2 pi^2 alpha t / L^2);
- scene_convection.yaml, every face cooled by a film of conductance H to air at Ta: the product of
  the three slabs' series (sections 3.11 and 1.15), each over the roots of b tan(b) = H l / k for a
  slab of half-thickness l;
- scene_conductivity.yaml, the ends held at T0 and T1, k(T) piecewise linear: at steady state the
  Kirchhoff transform U(T) = int_T0^T k dT is linear in x (only its last frame is compared);
- scene_regions.yaml, the bar at T0 with its part beyond x = a at T1 (a temperature region), every
  face insulated (section 3.3): T = Tm + sum_n 2 (T0 - T1) / (n pi) sin(n pi a / L) cos(n pi x / L)
  exp(-n^2 pi^2 alpha t / L^2), Tm = T0 a / L + T1 (1 - a / L);
- scene_radiation.yaml, a black body in surroundings at Ta, no convection: the lumped capacity's
  rho c V dT/dt = -eps sigma A (T^4 - Ta^4) in closed form for the bar's mean temperature (A / V of the
  bar: 1.1 / mm), the error as a fraction of T0 - Ta;
- scene_die.yaml, the lower face on a die at Td through an interface of conductance H, the other
  faces insulated: the slab series of half-thickness l = 4 mm (the bar and its mirror image), and
  the lumped capacity T = Td + (T0 - Td) exp(-H A t / (rho c V)) for the bar's mean temperature;
- scene_tables.yaml, the same with c(T) and rho(T) tables: the lumped rho0 V c(T) dT/dt = -H A(T) (T - Td),
  the contact area shrinking as (rho(T0) / rho(T))^(2/3), integrated by Runge-Kutta (only the lumped
  error is reported).
The error is the largest |T - T_exact| over the particles as a fraction of |T1 - T0|; with a die, the
lumped error is that of the mean temperature. Frames are read with meshio, independently of the
solver. Usage:
  heat_slab_check.py CASE [--json]
"""
import math
import re
from pathlib import Path

import meshio
import numpy as np
import yaml

from case_check import main_of


def fixed_ends(x, t, L, alpha, T0, T1, terms=400):
    s = np.zeros_like(x)
    for n in range(1, 2 * terms, 2):
        s += 4 / (n * math.pi) * np.sin(n * math.pi * x / L) * math.exp(-(n * math.pi / L) ** 2 * alpha * t)
    return T1 + (T0 - T1) * s


def steady(x, L, table, T0, T1):
    """T(x) with U(T(x)) = U(T1) x / L, U(T) = int_T0^T k dT for k piecewise linear through `table`."""
    Ts = np.linspace(T0, T1, 20001)
    k = np.interp(Ts, [p[0] for p in table], [p[1] for p in table])
    U = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(Ts))])
    return np.interp(U[-1] * x / L, U, Ts)


def radiated(t, rho_c_v_over_a, eps, T0, Ta):
    """The lumped temperature at t: t = C / (4 eps sigma Ta^3) [F(T0) - F(T)], F = ln((T + Ta)/(T - Ta)) + 2 atan(T/Ta),
    solved for T by bisection."""
    sigma = 5.670374419e-8
    F = lambda T: math.log((T + Ta) / (T - Ta)) + 2 * math.atan(T / Ta)
    c = rho_c_v_over_a / (4 * eps * sigma * Ta ** 3)
    lo, hi = Ta * (1 + 1e-12), T0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if c * (F(mid) - F(T0)) > t else (lo, mid)
    return 0.5 * (lo + hi)


def step(x, t, L, alpha, a, T0, T1, terms=2000):
    mean = T0 * a / L + T1 * (1 - a / L)
    s = np.full_like(x, mean)
    for n in range(1, terms):
        s += 2 * (T0 - T1) / (n * math.pi) * math.sin(n * math.pi * a / L) * np.cos(n * math.pi * x / L) * \
            math.exp(-(n * math.pi / L) ** 2 * alpha * t)
    return s


def film_slab(x, centre, l, bi, Fo, terms=200):
    """(T - Ta) / (T0 - Ta) in a slab |x - centre| <= l cooled through films on both faces, Biot number
    bi = H l / k, Fourier number Fo = alpha t / l^2."""
    s = np.zeros_like(x)
    for j in range(terms):  # the j-th root of b tan(b) = Bi lies in (j pi, j pi + pi / 2)
        lo, hi = j * math.pi + 1e-12, j * math.pi + math.pi / 2 - 1e-12
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if mid * math.tan(mid) < bi else (lo, mid)
        b = 0.5 * (lo + hi)
        c = 2 * math.sin(b) / (b + math.sin(b) * math.cos(b))
        s += c * np.cos(b * (x - centre) / l) * math.exp(-b * b * Fo)
    return s


def lumped_tables(t, W, H, rho0, c_table, rho_table, T0, Td, steps=20000):
    """The bar's lumped temperature at t with c(T) and rho(T) piecewise linear (held at their ends)."""
    cT = lambda T: np.interp(T, [p[0] for p in c_table], [p[1] for p in c_table])
    rT = lambda T: np.interp(T, [p[0] for p in rho_table], [p[1] for p in rho_table])
    f = lambda T: -H / W * (rT(T0) / rT(T)) ** (2 / 3) * (T - Td) / (rho0 * cT(T))
    T, h = T0, t / steps
    for _ in range(steps):
        k1 = f(T); k2 = f(T + h * k1 / 2); k3 = f(T + h * k2 / 2); k4 = f(T + h * k3)
        T += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6
    return float(T)


def check(case: Path) -> dict:
    scene = yaml.safe_load((case / "scene.resolved.yaml").read_text())
    mat = scene["material"]
    k = mat.get("conductivity") or mat["conductivity_table"][0][1]
    tables = "specific_heat_table" in mat
    rho, c = mat["density"], (mat["specific_heat_table"][0][1] if tables else mat["specific_heat"])
    T0 = scene["initial_conditions"]["temperature"]
    alpha, L = k / (rho * c), 0.02
    thermal = scene.get("thermal") or {}
    faces = thermal.get("fixed_faces") or []
    dies = [d for d in scene.get("dies") or [] if d.get("heat_transfer", 0) > 0]
    W = 0.004
    regions = scene["initial_conditions"].get("temperature_regions") or []
    if len(faces) == 2 and faces[0]["temperature"] != faces[1]["temperature"]:
        kind, T0, T1 = "steady", faces[0]["temperature"], faces[1]["temperature"]
    elif faces:
        kind, T1 = "fixed ends", faces[0]["temperature"]
    elif regions:
        kind, T1, edge = "step", regions[0]["temperature"], regions[0]["lo"][0]
    elif dies:
        kind, T1, H = ("die tables" if tables else "die"), dies[0]["temperature"], dies[0]["heat_transfer"]
    elif thermal.get("emissivity", 0) > 0 and thermal.get("convection", 0) == 0:
        kind, T1, eps = "radiation", thermal["ambient_temperature"], thermal["emissivity"]
    else:
        kind, T1, H = "convection", thermal["ambient_temperature"], thermal["convection"]
    pvd = (case / "vtk/case.pvd").read_text()
    frames = re.findall(r'timestep="([^"]+)"[^>]*name="part"[^>]*file="([^"]+)"', pvd)
    out = {"kind": kind, "alpha_m2_s": alpha, "frames": []}
    for t, name in frames:
        t = float(t)
        if t <= 0:
            continue
        m = meshio.read(case / "vtk" / name)
        x, T = m.points, m.point_data["temperature"].reshape(-1)
        if kind == "steady" and name != frames[-1][1]:
            continue
        if kind == "steady":
            exact = steady(x[:, 0], L, mat["conductivity_table"], T0, T1)
        elif kind == "fixed ends":
            exact = fixed_ends(x[:, 0], t, L, alpha, T0, T1)
        elif kind == "step":
            exact = step(x[:, 0], t, L, alpha, edge, T0, T1)
        elif kind == "radiation":  # V / A of the 20 x 4 x 4 mm bar: 320 / 352 mm
            exact = np.full_like(T, radiated(t, rho * c * 320.0 / 352.0 * 1e-3, eps, T0, T1))
        elif kind == "die":
            exact = T1 + (T0 - T1) * film_slab(x[:, 2], W, W, H * W / k, alpha * t / W**2)
        elif kind == "die tables":
            exact = np.full_like(T, lumped_tables(t, W, H, rho, mat["specific_heat_table"], mat["density_table"], T0, T1))
        else:
            exact = T1 + (T0 - T1) * np.prod([film_slab(x[:, i], c / 2, c / 2, H * c / (2 * k), alpha * t / (c / 2) ** 2)
                                              for i, c in enumerate((L, W, W))], axis=0)
        error = float(np.max(np.abs(T - exact)) / abs(T1 - T0))
        frame = {"time_s": t, "max_error": error, "mean_K": float(np.mean(T)), "exact_mean_K": float(np.mean(exact))}
        if kind == "die":  # lumped capacity: A / V = 1 / W (the lower face)
            lumped = T1 + (T0 - T1) * math.exp(-H * t / (rho * c * W))
            frame["lumped_error"] = abs(frame["mean_K"] - lumped) / abs(T1 - T0)
        if kind == "die tables":
            frame["lumped_error"] = abs(frame["mean_K"] - exact[0]) / abs(T1 - T0)
        out["frames"].append(frame)
    out["max_error"] = max(f["max_error"] for f in out["frames"])
    if kind.startswith("die"):
        out["max_lumped_error"] = max(f["lumped_error"] for f in out["frames"])
    return out


def summary(r: dict) -> str:
    return " ".join([r["kind"] + ":"] + [f"t={f['time_s']:g}s err={f['max_error']:.4f}" for f in r["frames"]] +
                    [f"max {r['max_error']:.4f}"] + ([f"lumped {r['max_lumped_error']:.4f}"] if "max_lumped_error" in r else []))


if __name__ == "__main__":
    main_of(__doc__, check, summary, needs=("vtk/case.pvd",), parts=("slab.geo",), what="heat slab (geometry/heat_slab)")
