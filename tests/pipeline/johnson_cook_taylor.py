"""The Taylor bar in Johnson-Cook OFHC copper (geometry/taylor_bar/scene_johnson_cook.yaml), heated by
its own plastic work, at 1.6 mm spacing to 20 us on 1 and 2 ranks:
- the heat balances the plastic work: the part's mass-weighted mean temperature rise is
  beta W_p / (rho c V) (every point's rise is beta times its plastic work over rho c), to round-off;
- the impact face is the hottest (its plastic strain the largest), the coolest point within 1 mK of the
  start's 293.15 K;
- the frames carry the temperature (merged by rkpost into the VTU), within the history's min and max;
- 1 and 2 ranks give the same particle positions and temperatures, bitwise (the fixed-point sums; the
  history's double sums over ranks, such as the volume, may differ in their last digit).
And a measured impact (geometry/taylor_bar/scene_jc1983.yaml: Johnson & Cook's 1983 copper cylinder at
190 m/s, 0.9 mm spacing, 100 us): its end state against the converged computation and the experiment."""
import json
import subprocess
import sys

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
scene = rkcase.ROOT / "geometry" / "taylor_bar" / "scene_johnson_cook.yaml"
sets = ["time.end=20e-6", "time.output_interval=10e-6"]
runs = {}
for ranks in (1, 2):
    case = tools.case(f"johnson_cook_r{ranks}")
    tools.prep(case, ranks, scene=scene, sets=["discretization.spacing=1.6e-3"])
    tools.solve(case, ranks, sets=sets)
    tools.post(case)
    runs[ranks] = case

case = runs[1]
lines = (case / "history.csv").read_text().splitlines()
names = lines[0].split(",")
last = dict(zip(names, map(float, lines[-1].split(","))))


volume = json.loads((case / "prep.json").read_text())["volume_m3"]  # the modeled quarter
rho, c, beta, T0 = 8960.0, 383.0, 0.9, 293.15
rise = last["temperature_mean"] - T0
expected = beta * last["plastic_work"] / (rho * c * volume)
# the mean is over the points' reference volumes, whose sum is the prep's volume. Measured 1.0e-9
# apart: history.csv's 10 digits of the mean temperature (about 3e-9 of the rise) bound it
rkcase.check(abs(rise - expected) <= 1e-8 * expected,
             f"the mean temperature rise {rise:.6f} K is beta W_p / (rho c V) = {expected:.6f} K")
rkcase.check(last["temperature_min"] - T0 < 1e-3 and last["temperature_max"] > T0 + 5 * rise,  # measured: 1.5e-5 K, 172 K
             f"the tail stays at {last['temperature_min']} K, the face is the hottest: {last['temperature_max']:.1f} K")

mesh = meshio.read(case / "vtk" / "frame_00002.vtu")
T = np.asarray(mesh.point_data["temperature"]).ravel()
z = mesh.points[:, 2]
rkcase.check(T.min() >= last["temperature_min"] - 1e-9 and T.max() <= last["temperature_max"] + 1e-9,
             f"the VTU's temperature {T.min():.2f}-{T.max():.2f} K lies within the points' range")
rkcase.check(T[z < 2e-3].mean() > T[z > 20e-3].mean() + 50,
             f"the impact end is hotter than the tail ({T[z < 2e-3].mean():.1f} against {T[z > 20e-3].mean():.1f} K)")
other = meshio.read(runs[2] / "vtk" / "frame_00002.vtu")  # particles in global-id order in both
same = np.array_equal(mesh.points, other.points) and np.array_equal(T, np.asarray(other.point_data["temperature"]).ravel())
rkcase.check(same, "1 and 2 ranks give the same positions and temperatures, bitwise")

# Johnson & Cook's cylinder (L0 25.4 mm, D0 7.62 mm, 190 m/s): measured L_f 16.21 mm and face radius
# 6.78 mm (scripts/taylor_metrics.py, EXPERIMENT). Measured 2026-12-02 with the same law, 2 ranks:
#   spacing 0.9 / 0.6 / 0.45 mm (1 073 / 3 913 / 9 633 particles): r_f 7.159 / 7.205 / 7.229 mm,
#   L_f 17.284 / 17.305 / 17.317 mm, converging from below: the law predicts the bar 6.9 % long and
#   its face 6.6 % wide at 0.45 mm.
# The 0.9 mm run is held to its converged value within twice its distance from it (r_f 0.97 %, L_f
# 0.19 %), and to the experiment's band that the converged law gives (within 8 %); the deviation from
# the experiment is the law's (its constants were fitted to torsion and Hopkinson-bar tests, not to
# this one) and is reported, not tuned away.
case = tools.case("johnson_cook_1983")
tools.prep(case, 1, scene=rkcase.ROOT / "geometry" / "taylor_bar" / "scene_jc1983.yaml")
tools.solve(case, 1)
tools.post(case)
m = json.loads(subprocess.run([sys.executable, rkcase.ROOT / "scripts" / "taylor_metrics.py", case, "--json"],
                              capture_output=True, text=True, check=True).stdout)
converged = {"footprint_radius_mm": (7.229, 0.02), "final_length_mm": (17.317, 0.004)}
measured = {"footprint_radius_mm": 0.5 * 1.78 * 7.62, "final_length_mm": 0.638 * 25.4}
for key, (value, tol) in converged.items():
    rkcase.check(abs(m[key] / value - 1) < tol, f"{key}: {m[key]:.3f} mm, the converged law's {value} within {tol:.1%}")
    off = m[key] / measured[key] - 1
    rkcase.check(0 < off < 0.08, f"{key}: {m[key]:.3f} mm against the measured {measured[key]:.2f} mm ({off:+.1%}, the law's)")
