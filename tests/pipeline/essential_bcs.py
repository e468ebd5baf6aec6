"""Essential boundary conditions: the nodal and the exact (transformation) method.

1. Patch test on a cube of structured hexahedra (h = 1.25 mm, support
   radius a = 2 h): the homogeneous motion v = G X, G = diag(10, -3, -3) 1/s, given as the initial
   velocity and held by the boundary conditions (three symmetry planes, three prescribed faces).
   The exact solution keeps v = G X with a uniform stress, so an integration that is consistent
   for linear fields leaves no force on a particle whose support does not reach the boundary.
   a. First step (t = 0.1 us, strain 1e-6): the particles at least a from every face (125) keep
      v = G X to round-off with nodal integration (SCNI, consistent); with Gauss cells of order
      1, 2, 3 (not consistent) they move off it by the quadrature error, asserted at its measured
      level. The same with either method: the boundary cannot reach them within one step. The
      nodal method holds the constrained velocity components of the boundary particles'
      coefficients exactly; the exact method holds u^h at them to round-off.
   b. 20 us (about 100 steps, the waves from the boundary layer cross the cube several times):
      RK shape functions do not interpolate, so holding the boundary at its particles (either
      method) does not give the boundary integral of the traction that the exact solution
      needs, and the field departs from linear. Its error levels are asserted as measured, the
      mean stress and the face_x reaction against the closed form sigma_xx A, the exact method
      holds the prescribed displacements at the boundary particles to round-off, the nodal
      method holds their coefficients (its u^h misses them by a measured amount), and the
      exact method beats the nodal one.
2. A wedge with non-axis-aligned symmetry planes (the wheel-forging sector pressed 0.3 mm): with
   the exact method the cut faces' particles stay on their planes to round-off; the nodal method
   moves their coefficients along the planes to round-off, and how far the material at them
   leaves the planes is printed.
3. Symmetry: the quarter Taylor bar (two symmetry planes) against the whole bar at the 2007
   paper's spacing (0.9 mm), 30 us into the impact: the quarter's footprint radius reads 0.35-0.45 % wider than the
   whole bar's (within 0.5 %, held at its measurement), radius, length, steps and wall time of each
   printed side by side.
4. Bad boundary input: a face that holds no particle, a plane through the inside of the part, two
   faces that prescribe different motions of one particle: one clear error each.
"""
import csv
import json

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
data = rkcase.ROOT / "tests" / "pipeline" / "data" / "patch_cube"
geometry = rkcase.ROOT / "geometry"


def last_row(case):
    with open(case / "history.csv") as f:
        return list(csv.DictReader(f))[-1]


def last_frame(case):
    frames = sorted((case / "vtk").glob("frame_*.vtu"))
    return meshio.read(frames[-1])


# ---- 1. patch test
E, nu, L = 200e9, 0.3, 10e-3
G = np.diag([10.0, -3.0, -3.0])
lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
speed = np.abs(G).max() * L  # the largest velocity, 0.1 m/s
QUADRATURES = {"scni": ["discretization.integration=nodal"], "gauss1": ["discretization.gauss_order=1"],
               "gauss2": ["discretization.gauss_order=2"], "gauss3": ["discretization.gauss_order=3"],
               "rule4": ["discretization.cell_rule=four_point"], "rule6": ["discretization.cell_rule=six_point"]}
METHODS = ("nodal", "transformation")


def patch_run(method, quad, t_end):
    case = tools.case(f"patch_{method}_{quad}_{round(t_end * 1e9)}ns")
    tools.prep(case, 1, scene=data / "scene.yaml", sets=[f"discretization.ebc_method={method}"] + QUADRATURES[quad])
    # the first step: one frame at its end; 20 us: the scene's frames every 10 us
    tools.solve(case, 1, sets=[f"time.end={t_end}"] + ([f"time.output_interval={t_end}"] if t_end < 1e-6 else []))
    tools.post(case)
    m = last_frame(case)
    u = np.asarray(m.point_data["displacement"])
    X = np.asarray(m.points) - u
    return case, m, X, u, np.asarray(m.point_data["velocity"])


# 1a. The first step. Measured on 1 and 2 ranks (the same), largest |v - G X| of the core over the
# largest velocity: SCNI 2.42e-11 at strain 1e-6, 1.87e-12 at 1e-5, 3.07e-13 at 1e-4 (G scaled up:
# it falls as the strain grows, so it is the round-off of F = I + H carrying the strain, 2.2e-16 /
# 1e-6 = 2.2e-10 of it: the bound); Gauss cells 4.9114e-4 (order 1), 8.0246e-5 (2), 8.5465e-6 (3),
# at the core's particles nearest the boundary, whose shape functions the boundary reshapes (3.75 mm
# and more from every face: 1.5e-6, 1.7e-6, 8.1e-7). Their tolerance, 5 %, is far above their
# round-off and far below the 6x between orders: the check tells which quadrature ran. The hexahedra's
# four- and six-point rules (discretization.cell_rule, 2026-12-07): 8.0246e-5, the 2x2x2 rule's level to
# its five digits (on this regular grid the core's first-step error does not tell the two apart; their
# 20-us levels below do, 2x and more apart), and 9.5761e-5.
# The nodal method sets a held component of a coefficient's velocity to (prescribed - e.u) / dt, so
# it carries the rounding of u: |u| 2.2e-16 / dt, 2.3e-14 of the velocity at 20 us (the measured
# 4e-15 to 2.5e-14; 5e-14 on the wedge below, |u| 0.33 mm at 10 m/s): the bound 1e-12 is round-off;
# with the nodal method's velocity update removed they moved off by 3.2e-2 in the first step. The exact method's u^h
# is a 30-term row sum of the coefficients: 1e-13 of the imposed displacement (measured 6.4e-16).
# Re-measured 2026-12-07 when a frame's velocity became v^n interpolated to its time (the one step is
# shortened to land on 0.1 us, the next would be 2.8x as long, and the mean of the half steps' velocities
# gave that next step's acceleration that weight): every level times 0.6861, 4.9114e-4 -> 3.3699e-4 and so on.
CORE_LEVEL = {"gauss1": 3.3699e-4, "gauss2": 5.5060e-5, "gauss3": 5.8641e-6, "rule4": 5.5060e-5, "rule6": 6.5705e-5}
core_error = {}
for quad in QUADRATURES:
    for method in METHODS:
        case, m, X, u, v = patch_run(method, quad, 1e-7)
        steps = json.loads((case / "solve.json").read_text())["steps"]
        rkcase.check(steps == 1, f"patch first step, {method}, {quad}: one step to 0.1 us")
        distance = np.minimum(X, L - X).min(axis=1)
        core = distance > 2.5e-3 - 1e-9
        off = np.abs(v - X @ G.T) / speed
        core_error[method, quad] = off[core].max()
        print(f"patch first step {method:15s} {quad:6s} core ({core.sum()}) {core_error[method, quad]:.4e}, "
              f"boundary layer {off[~core].max():.3e}")
        if method == "nodal":  # the constrained components of the boundary particles' coefficients
            held = max(off[np.abs(X[:, i] - c) < 1e-9, i].max() for i in range(3) for c in (0.0, L))
            rkcase.check(held < 1e-12, f"patch first step, nodal, {quad}: the boundary coefficients move as prescribed "
                         f"to {held:.1e} of {speed} m/s (round-off; the boundary layer is off by {off[~core].max():.1e})")
        else:
            ebc = json.loads((case / "solve.json").read_text())["max_ebc_error_m"] / (speed * 1e-7)
            rkcase.check(ebc < 1e-13, f"patch first step, transformation, {quad}: u^h holds the prescribed "
                         f"displacement at the boundary particles to {ebc:.1e} of it (round-off)")
for quad in QUADRATURES:
    a, b = core_error["nodal", quad], core_error["transformation", quad]
    rkcase.check(abs(a - b) <= 1e-12 + 1e-9 * a, f"patch first step, {quad}: the core is the same with either method "
                 f"({a:.4e}, {b:.4e}): the boundary is out of its reach")
    if quad == "scni":
        rkcase.check(a < 2.2e-10, f"patch first step, SCNI (consistent): the core keeps v = G X to {a:.2e} of the "
                     "velocity, round-off (< 2.2e-10)")
    else:
        rkcase.check(abs(a / CORE_LEVEL[quad] - 1) < 0.05, f"patch first step, {quad} (not consistent): the core "
                     f"moves off v = G X by {a:.4e} of the velocity, the measured {CORE_LEVEL[quad]:.4e} within 5 %")

# 1b. 20 us. Measured at the scene's CFL 0.9 (and 0.8: each level moved by at most 0.32 %, the
# tolerance 1 % is about twice that, rounded up): the largest |u - t G X| over the largest
# displacement, the spread of the von Mises stress over its closed form, and the nodal method's
# miss |u^h(X_I) - prescribed| at the boundary particles over the imposed 2 um.
t_end = 20e-6
eps = t_end * np.diag(G)
sigma = lam * eps.sum() + 2 * mu * eps  # small strain (2e-4): finite-strain terms ~2e-4 relative
von_mises, imposed = abs(sigma[0] - sigma[1]), speed * t_end
# (the displacements are the material's, u^h(X_I), at every particle: re-measured 2026-12-01 when the
# results changed from the coefficients d_I at the unconstrained particles to u^h(X_I); the SCNI stress
# spreads re-measured 2026-12-02 when particle values became positive-weight averages: 1.6054e-1 ->
# 1.5791e-1 and 2.8156e-2 -> 2.7773e-2, the Gauss rows moved by less than 0.1 %)
LEVEL = {("nodal", "scni"): (2.2041e-2, 1.5791e-1, 5.8365e-3), ("transformation", "scni"): (5.4515e-3, 2.7773e-2, None),
         ("nodal", "gauss1"): (2.3312e-1, 1.0728e-1, 9.5040e-2), ("transformation", "gauss1"): (1.7061e-1, 4.6393e-2, None),
         ("nodal", "gauss2"): (1.8230e-2, 1.0811e-1, 3.4408e-3), ("transformation", "gauss2"): (2.8393e-3, 1.2337e-2, None),
         ("nodal", "gauss3"): (1.7233e-2, 1.0213e-1, 3.7048e-3), ("transformation", "gauss3"): (3.2549e-3, 1.3183e-2, None),
         ("nodal", "rule4"): (3.9255e-2, 1.2585e-1, 7.8680e-3), ("transformation", "rule4"): (2.1486e-2, 4.9607e-2, None),
         ("nodal", "rule6"): (1.5348e-2, 8.6609e-2, 3.4647e-3), ("transformation", "rule6"): (3.8698e-3, 1.6994e-2, None)}
results = {}
print(f"{'method':15s} {'quad':>6s} {'u error':>10s} {'vm spread':>10s} {'vm mean/exact':>13s} {'face_x force/exact':>18s} {'ebc error':>10s}")
for quad in QUADRATURES:
    for method in METHODS:
        case, m, X, u, v = patch_run(method, quad, t_end)
        exact = t_end * X @ G.T
        vm = np.asarray(m.point_data["von_mises"]).ravel()
        row = last_row(case)
        solve = json.loads((case / "solve.json").read_text())
        r = {"u_error": np.abs(u - exact).max() / np.abs(exact).max(),
             "vm_spread": (vm.max() - vm.min()) / von_mises,
             "vm_mean": vm.mean() / von_mises,
             "force": float(row["face_x.fx"]) / (sigma[0] * L * L),
             "ebc_error": solve["max_ebc_error_m"] / imposed,
             "finite": bool(np.isfinite(u).all() and np.isfinite(vm).all())}
        if method == "nodal":
            r["held"] = max(np.abs(v - X @ G.T)[np.abs(X[:, i] - c) < 1e-9, i].max() for i in range(3) for c in (0.0, L)) / speed
        results[method, quad] = r
        print(f"{method:15s} {quad:>6s} {r['u_error']:10.4e} {r['vm_spread']:10.4e} {r['vm_mean']:13.6f} "
              f"{r['force']:18.6f} {r['ebc_error']:10.4e}")

for (method, quad), r in results.items():
    rkcase.check(r["finite"], f"patch 20 us {method} {quad}: completes with finite fields")
    u_level, spread_level, miss_level = LEVEL[method, quad]
    rkcase.check(abs(r["u_error"] / u_level - 1) < 0.01 and abs(r["vm_spread"] / spread_level - 1) < 0.01,
                 f"patch 20 us {method} {quad}: displacement error {r['u_error']:.4e} and stress spread "
                 f"{r['vm_spread']:.4e}, the measured {u_level:.4e} and {spread_level:.4e} within 1 %")
    if method == "transformation":
        rkcase.check(r["ebc_error"] < 1e-13, f"patch 20 us, transformation, {quad}: the prescribed displacements hold "
                     f"at the boundary particles to {r['ebc_error']:.1e} of the imposed {1e6 * imposed:.1f} um (round-off)")
    else:
        rkcase.check(r["held"] < 1e-12, f"patch 20 us, nodal, {quad}: the boundary particles' coefficients move as "
                     f"prescribed to {r['held']:.1e} of {speed} m/s (round-off)")
        rkcase.check(abs(r["ebc_error"] / miss_level - 1) < 0.01,
                     f"patch 20 us, nodal, {quad}: u^h misses the prescribed displacement by {r['ebc_error']:.4e} of it, "
                     f"the measured {miss_level:.4e} within 1 % (RK shape functions do not interpolate)")
# Against the closed form (orders 2, 3, SCNI and the four- and six-point rules; order 1 is far off): measured
# within 0.063 % (mean von Mises stress) and 0.060 % (the exact method's face_x reaction); 0.1 % is about
# twice that.
for quad in ("scni", "gauss2", "gauss3", "rule4", "rule6"):
    for method in METHODS:
        r = results[method, quad]
        rkcase.check(abs(r["vm_mean"] - 1) < 0.001, f"patch 20 us {method} {quad}: mean von Mises stress "
                     f"{r['vm_mean']:.6f} of the closed form {von_mises / 1e6:.2f} MPa (within 0.1 %)")
    r, n = results["transformation", quad], results["nodal", quad]
    rkcase.check(abs(r["force"] - 1) < 0.001, f"patch 20 us transformation {quad}: face_x reaction "
                 f"{r['force']:.6f} of sigma_xx A = {sigma[0] * L * L:.0f} N (within 0.1 %)")
    rkcase.check(r["u_error"] < n["u_error"] and r["vm_spread"] < n["vm_spread"],
                 f"patch 20 us {quad}: transformation beats nodal (u error {100 * r['u_error']:.2f} % vs "
                 f"{100 * n['u_error']:.2f} %, stress spread {100 * r['vm_spread']:.2f} % vs {100 * n['vm_spread']:.2f} %)")

# ---- 2. wedge: the wheel sector, symmetry planes at 30 and 60 degrees
off_plane = {}
for method in ("nodal", "transformation"):
    case = tools.case(f"wedge_{method}")
    tools.prep(case, 2, scene=geometry / "wheel_forging" / "scene.yaml",
               sets=["discretization.spacing=4e-3", f"discretization.ebc_method={method}", "reference_updates.strain=0"])
    tools.solve(case, 2, sets=["time.end=30e-6", "time.output_interval=30e-6"])
    tools.post(case)
    m = last_frame(case)
    x = np.asarray(m.points)
    X = x - np.asarray(m.point_data["displacement"])
    v = np.asarray(m.point_data["velocity"])  # the coefficients' (the nodal method holds them on the planes)
    worst, moved, held = 0.0, 0.0, 0.0
    for angle in (30, 60):
        n = np.array([-np.sin(np.radians(angle)), np.cos(np.radians(angle)), 0.0])
        on = np.abs(X @ n) < 1e-9
        rkcase.check(on.sum() > 10, f"wedge {method}: {on.sum()} particles on the {angle}-degree face")
        worst = max(worst, np.abs(x[on] @ n).max())
        moved = max(moved, np.linalg.norm(x[on] - X[on], axis=1).max())
        held = max(held, np.abs(v[on] @ n).max() / np.abs(v).max())
    off_plane[method] = (worst, moved, held)
worst, moved, _ = off_plane["transformation"]
rkcase.check(moved > 1e-5 and worst < 1e-12,
             f"wedge transformation: cut-face particles moved up to {1e3 * moved:.3f} mm and stay on their planes "
             f"within {worst:.1e} m")
worst_n, moved_n, held_n = off_plane["nodal"]
rkcase.check(held_n < 1e-12, f"wedge nodal: the cut-face particles' coefficients move along their planes (normal "
             f"velocity {held_n:.1e} of the largest, round-off)")
print(f"wedge nodal: the material at the cut-face particles leaves their planes by up to {1e6 * worst_n:.2f} um "
      f"({100 * worst_n / moved_n:.2f} % of their motion)")

# ---- 3. quarter against whole Taylor bar (0.9 mm, 30 us: the footprint has reached 94 % of its final size)
import taylor_metrics  # noqa: E402

radius = {}
for name, scene, method in (("full", "scene_full.yaml", "nodal"), ("quarter_nodal", "scene.yaml", "nodal"),
                            ("quarter_transformation", "scene.yaml", "transformation")):
    case = tools.case(f"taylor_{name}")
    tools.prep(case, 2, scene=geometry / "taylor_bar" / scene, sets=[f"discretization.ebc_method={method}"])
    tools.solve(case, 2, sets=["time.end=30e-6", "time.output_interval=10e-6"])
    tools.post(case)
    met = taylor_metrics.metrics(case)
    solve = json.loads((case / "solve.json").read_text())
    radius[name] = met["footprint_radius_mm"]
    print(f"Taylor {name:24s} r_f {met['footprint_radius_mm']:.3f} mm  L {met['final_length_mm']:.3f} mm  "
          f"{solve['steps']} steps  {solve['wall_s']:.1f} s  ebc error {solve['max_ebc_error_m']:.1e} m")
# Measured 2026-12-02 with the benchmark's wall (the impact face held on it, sliding): the quarter
# bar reads +0.45 % (nodal EBCs) and +0.35 % (exact EBCs) wider than the whole bar at 30 us, within
# the 0.5 % that the two should agree to; the planes' essential BCs act on truncated supports
# (mirror particles would remove the rest). With a wall that let the rim lift off, the deviations
# were +0.71 % and +1.24 %. Each is held within 0.2 % of its measurement (the remaining bias is
# deterministic: rank counts give bitwise equal runs) and below 0.5 %.
MEASURED_DEVIATION = {"quarter_nodal": 0.0045, "quarter_transformation": 0.0035}
for name in ("quarter_nodal", "quarter_transformation"):
    dev = radius[name] / radius["full"] - 1
    rkcase.check(abs(dev - MEASURED_DEVIATION[name]) < 0.002 and abs(dev) < 0.005,
                 f"{name.replace('_', ' ')}: footprint radius {radius[name]:.3f} mm against the whole bar's "
                 f"{radius['full']:.3f} mm ({100 * dev:+.2f} %, the measured {100 * MEASURED_DEVIATION[name]:+.2f} % "
                 "within 0.2 %, and within 0.5 %)")

# ---- 4. bad boundary input
cube = data / "scene.yaml"
bad = [
    (["boundaries.fixed_faces=[{name: ghost, point: [0.5, 0, 0], normal: [1, 0, 0]}]"],
     "boundaries.fixed_faces 'ghost': no particle of the part lies on this plane"),
    (["boundaries.fixed_faces=[{name: cut, point: [5.0e-3, 0, 0], normal: [1, 0, 0]}]"],
     "inside the part"),
    (["boundaries.fixed_faces=[{name: base, point: [0, 0, 0], normal: [1, 0, 0]}]"],
     "prescribe different motions"),
]
for k, (sets, expected) in enumerate(bad):
    case = tools.case(f"bad_{k}")
    tools.prep(case, 2, scene=cube, sets=["discretization.spacing=2.5e-3"])
    p = tools.solve(case, 2, sets=sets, expect_ok=False)
    message = p.stdout + p.stderr
    line = next((l for l in message.splitlines() if "rksolve: error" in l), "")
    rkcase.check(p.returncode != 0 and expected in line and message.count("rksolve: error") == 1,
                 f"bad boundary input refused with one clear error: {line}")
