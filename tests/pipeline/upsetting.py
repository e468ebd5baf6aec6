"""Frictionless upsetting of an aluminium cylinder at a coarse resolution against the closed form:
die force F = sigma(ep) A0 H0 / H and diameter D0 sqrt(H0/H) at 10-50 %
height reduction, quasi-static (kinetic/internal < 1 %); the normalized Cockcroft-Latham damage stays
near zero (homogeneous compression has no tensile principal stress); and a short run on 2 ranks equal to
1 rank."""
import json

import meshio
import numpy as np

import rkcase
from upsetting_check import check

tools = rkcase.tools_from_argv()
scene = rkcase.ROOT / "geometry" / "upsetting" / "scene.yaml"
coarse = ["discretization.spacing=2e-3"]
case = tools.case("upsetting_coarse")
tools.prep(case, 1, scene=scene, sets=coarse)
tools.solve(case, 1, sets=["time.mass_scaling_dt=3e-7", "time.output_interval=1e-3", "damage.cockcroft_latham.critical=0",
                          "damage.oyane.a=0.3"])
tools.post(case)
res = check(case)
print(json.dumps(res, indent=2))
for f in res["force"]:
    tol = 0.025 if f["reduction"] < 0.15 else 0.015
    rkcase.check(abs(f["error"]) < tol, f"{100 * f['reduction']:.0f} % reduction: force {f['force_kN']:.1f} kN, "
                 f"exact {f['exact_kN']:.1f} kN ({100 * f['error']:+.2f} %, tolerance {100 * tol:.1f} %)")
rkcase.check(len(res["force"]) == 5, "reached 50 % reduction")
rkcase.check(abs(res["diameter_error"]) < 0.005, f"diameter {res['diameter_mm']:.2f} mm ({100 * res['diameter_error']:+.2f} %)")
rkcase.check(res["max_kinetic_internal_ratio"] < 0.01, f"quasi-static: KE/IE <= {100 * res['max_kinetic_internal_ratio']:.2f} %")
last = meshio.read(sorted((case / "vtk").glob("frame_*.vtu"))[-1]).point_data
ratio = float((last["damage_cockcroft_latham"].ravel() / np.maximum(last["eq_plastic_strain"].ravel(), 0.1)).max())
# measured 2026-12-02: 0.049 of the plastic strain at most, from the lateral stresses' scatter about 0
# (2.5 % of sigma_eq at 2 mm); with friction the barrel's equator reaches 0.13 (upsetting_friction.py)
rkcase.check(ratio < 0.09, f"frictionless: Cockcroft-Latham at most {ratio:.3f} of the plastic strain")
# Oyane with a = 0.3: sigma_m / sigma_eq = -1/3 in homogeneous compression, so no increment but for
# the same scatter: measured 2026-12-02 0.009 of the plastic strain at most (with friction it grows at
# the barrel's equator, upsetting_friction.py)
oyane = float((last["damage_oyane"].ravel() / np.maximum(last["eq_plastic_strain"].ravel(), 0.1)).max())
rkcase.check(oyane < 0.02, f"frictionless: Oyane (a = 0.3) at most {oyane:.3f} of the plastic strain")
# Particle fields are positive-weight averages of the points' values (w_g max(N_I(X_g), 0)), so a
# particle's von Mises stress stays at its points' flow stress, sigma_y = K (eps0 + ep)^n at the
# particle's plastic strain (the law is concave: the points' average flow stress is at most the flow
# stress of their average strain). Measured at 50 % reduction (2 mm, 1 rank): at most 1.068 of it;
# bound: twice that excess over 1.
import yaml  # noqa: E402
mat = yaml.safe_load((case / "scene.resolved.yaml").read_text())["material"]
flow = mat["strength"] * (mat["reference_strain"] + last["eq_plastic_strain"].ravel()) ** mat["exponent"]
over = float((last["von_mises"].ravel() / flow).max())
rkcase.check(over <= 1.14, f"particle von Mises at most {over:.4f} x the flow stress at its plastic strain (bound 1.14)")
# and, the weights being positive, the von Mises stress of a particle's averaged tensor is at most its
# averaged von Mises stress (a convex function of the stress: Jensen). Measured: at least 1.75e-5
# below it on every particle; the RK values themselves as weights (some negative) put it 0.24 % above
# (the flow-stress ratio above stays 1.068 with them on this case). Bound: 1e-6 above (round-off).
s = np.asarray(last["stress"])
dev = s[:, :3] - s[:, :3].mean(axis=1, keepdims=True)
q = np.sqrt(1.5 * ((dev ** 2).sum(axis=1) + 2 * (s[:, 3:] ** 2).sum(axis=1)))
excess = float((q / last["von_mises"].ravel() - 1).max())
rkcase.check(excess <= 1e-6, f"a particle's stress tensor has a von Mises stress at most its von_mises field "
             f"({excess:+.2e} relative, bound 1e-6)")

frames = {}
for ranks in (1, 2):
    c = tools.case(f"upsetting_r{ranks}")
    tools.prep(c, ranks, scene=scene, sets=coarse)
    tools.solve(c, ranks, sets=["time.end=0.5e-3", "time.output_interval=0.5e-3", "time.mass_scaling_dt=3e-7"])
    tools.post(c)
    m = meshio.read(c / "vtk" / "frame_00001.vtu")
    order = np.argsort(m.point_data["global_id"].ravel())
    frames[ranks] = (m.points[order], m.point_data["velocity"][order])
rkcase.check(np.array_equal(frames[1][0], frames[2][0]) and np.array_equal(frames[1][1], frames[2][1]),
             "upsetting with die contact: 2 ranks bitwise equal to 1 rank")

die = meshio.read(sorted((case / "vtk").glob("die_die_*.vtu"))[-1])
rkcase.check(die.cells[0].type == "triangle" and len(die.cells[0].data) > 0, "the die is written as triangles for ParaView")
rkcase.check(abs(die.points[:, 2].min() - 5e-3) < 1e-9, f"the die face at its final stroke: z = {1e3 * die.points[:, 2].min():.3f} mm")

# Flow lines (output.flow_lines, the axial section x = 0, lines along the axis 2.5 mm apart): the
# particles on them at t = 0 lie on their lines, and frictionless upsetting is homogeneous, so each
# line stays straight and moves out to y0 sqrt(H0 / H). Measured 2026-12-02 at 2 mm and 50 %: within
# 1.2 % (the rim's line, on the free surface), 0.65 % and 0.27 % inside, 7 um about the axis.
flows = sorted((case / "vtk").glob("flow_axial_*.vtu"))
f0, f1 = meshio.read(flows[0]), meshio.read(flows[-1])
height = 2 * meshio.read(sorted((case / "vtk").glob("frame_*.vtu"))[-1]).points[:, 2].max()
line = f1.point_data["line"].ravel()
worst, count = 0.0, int(line.max()) + 1
for k in range(count):
    on = line == k
    y0 = f0.points[on, 1]
    rkcase.check(abs(y0 - y0.mean()).max() < 1e-9 and abs(y0.mean() / 2.5e-3 - round(y0.mean() / 2.5e-3)) < 1e-6
                 and abs(f0.points[on, 0]).max() < 1e-9, f"line {k}: {on.sum()} particles on y = {1e3 * y0.mean():.2f} mm at t = 0")
    expect = y0.mean() * np.sqrt(20e-3 / height)
    worst = max(worst, abs(f1.points[on, 1] - expect).max() / max(expect, 2.5e-3))
rkcase.check(count == 5 and worst < 0.025, f"{count} flow lines: straight and at y0 sqrt(H0/H) within {100 * worst:.2f} %")
