"""Coulomb friction against the closed form: an elastic block slides on a rigid floor under
a body force g = 1e5 m/s^2 with v0 = 10 m/s and mu = 0.5. Closed form: v = v0 - mu g t, sliding
distance v0 t - mu g t^2 / 2 until it stops at t = v0 / (mu g) = 0.2 ms, 1.0 mm from where it was."""
import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
scene = rkcase.ROOT / "tests" / "pipeline" / "data" / "sliding_block" / "scene.yaml"
case = tools.case("sliding_block")
tools.prep(case, 1, scene=scene)
tools.solve(case, 1)
tools.post(case)
v0, mu, g = 10.0, 0.5, 1e5
frames = [meshio.read(case / "vtk" / f"frame_{k:05d}.vtu") for k in range(4)]
x0 = frames[0].points[:, 0].mean()
slide = [f.points[:, 0].mean() - x0 for f in frames]
speed = [f.point_data["velocity"][:, 0].mean() for f in frames]
t = 1e-4
rkcase.check(abs(slide[1] / (v0 * t - 0.5 * mu * g * t * t) - 1) < 0.02,
             f"slid {1e3 * slide[1]:.4f} mm at 0.1 ms (closed form 0.7500 mm, 2 %)")
rkcase.check(abs(speed[1] / (v0 - mu * g * t) - 1) < 0.03, f"speed {speed[1]:.3f} m/s at 0.1 ms (closed form 5.000, 3 %)")
rkcase.check(abs(speed[3]) < 0.05, f"at rest after the stop time: {speed[3]:.4f} m/s")
rkcase.check(abs(slide[3] / (v0 * v0 / (2 * mu * g)) - 1) < 0.05,
             f"total slide {1e3 * slide[3]:.4f} mm (closed form 1.0000 mm, 5 %)")
rkcase.check(abs(slide[3] - slide[2]) < 0.05 * slide[3], "sticks once stopped")

# Health check: with the body force reversed the block flies off the floor; the run stops with the
# particle that left the box of the part and the dies, and a last frame to look at.
p = tools.solve(case, 1, sets=["loads.gravity=[0,0,1e6]"], expect_ok=False)
rkcase.check(p.returncode != 0 and "has left the box of the part and the dies" in p.stderr and "particle " in p.stderr
             and "(last frame written)" in p.stderr, f"a particle leaving the tools stops the run: {p.stderr.strip()[:200]}")
