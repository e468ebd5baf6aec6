"""Dies driven by their press (geometry/upsetting/scene_hammer.yaml, scene_hydraulic.yaml: an aluminium
billet D0 = 20 mm, H0 = 10 mm on a frictionless anvil, a quarter modeled, 2.5 mm spacing):
- hammer, one blow of 344 J from a 100 kg ram: the ram stops and the run ends there; the energy it
  delivered equals the part's internal + kinetic energy (1 %); the height reduction is the one where
  homogeneous upsetting has absorbed that energy, V int sigma d ep + elastic = E (closed form with the
  power law; 2 %); the same on 2 ranks bitwise; a restart mid-blow ends bitwise equal;
- two blows of 172 J reach the stroke of one of 344 J;
- hydraulic press at 0.1 m/s with a 150 kN limit and a 500 kg ram: it stalls short of its stroke where
  the ram's kinetic energy is spent against the load above the limit, int (F(s) - F_lim) ds = M v^2 / 2
  from where the closed-form force reaches the limit; the peak load exceeds the limit by the ram's
  inertial overshoot v sqrt(M dF/ds) at most; a stall is a warning in solve.json and report.md;
- with a high limit it stops at its stroke; with a power limit, speed x force stays at that power, and
  the same on 2 ranks bitwise;
- the die's contact loads per triangle sum to its force; the triangles it touched cover the billet's end;
- bad input: no blow energy, a ram too light for the contact, a symmetry plane across the ram's motion."""
import csv
import json
import math
import shutil

import meshio
import numpy as np

import rkcase

tools = rkcase.tools_from_argv()
GEO = rkcase.ROOT / "geometry" / "upsetting"
E, K, EPS0, N = 71e9, 576.79e6, 0.01658, 0.3593
R0, H0 = 10e-3, 10e-3
A0, V = math.pi * R0 ** 2, math.pi * R0 ** 2 * H0
SPACING = ["discretization.spacing=2.5e-3"]


def rows(case):
    return list(csv.DictReader(open(case / "history.csv")))


def last_frame(case):
    m = meshio.read(sorted((case / "vtk").glob("frame_*.vtu"))[-1])
    order = np.argsort(m.point_data["global_id"].ravel())
    return m.points[order], m.point_data["velocity"][order]


def sigma(ep):
    return K * (EPS0 + ep) ** N


def bisect(f, lo, hi):
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def blow_reduction(energy):
    """Homogeneous frictionless upsetting: the plastic strain where V (int sigma d ep + sigma^2 / 2E)
    is the energy, and the height reduction 1 - exp(-(ep + sigma / E))."""
    work = lambda ep: V * (K * ((EPS0 + ep) ** (N + 1) - EPS0 ** (N + 1)) / (N + 1) + sigma(ep) ** 2 / (2 * E))
    ep = bisect(lambda e: work(e) - energy, 0, 2)
    return 1 - math.exp(-(ep + sigma(ep) / E))


def force(stroke):
    """The closed form F = sigma(ep) A0 H0 / H, ep = ln(H0 / H) - sigma / E."""
    H = H0 - stroke
    s = 300e6
    for _ in range(100):
        s = sigma(math.log(H0 / H) - s / E)
    return s * A0 * H0 / H


# --- hammer: one blow ---
prep = tools.case("hammer_prep")
tools.prep(prep, 1, scene=GEO / "scene_hammer.yaml", sets=SPACING)
prep2 = tools.case("hammer_prep2")
tools.prep(prep2, 2, scene=GEO / "scene_hammer.yaml", sets=SPACING)


def copy(src, name):
    dst = tools.case(name)
    shutil.copytree(src, dst)
    return dst


one = copy(prep, "hammer")
out = tools.solve(one, 1)
tools.post(one)
h = rows(one)
end = h[-1]
t_end = float(end["time"])
said = json.load(open(one / "solve.json"))["presses"][0]
rkcase.check(float(end["ram.speed"]) == 0 and t_end < 3.9e-3 and "stopped after 1 of 1 blows" in said and said in out.stderr,
             f"the ram stops at {1e3 * t_end:.3f} ms and the run ends there: {said}")
delivered = float(end["ram.delivered"])
# the ram's lost kinetic energy is the work of the part's reaction on it, sum dt_avg R vbar, up to its
# last step (where the speed is clamped at 0): measured 344.0000001 J
rkcase.check(abs(delivered - 344) < 1e-3 * 344, f"delivered {delivered:.4f} J of the blow's 344 J")
absorbed = 4 * (float(end["internal"]) + float(end["kinetic"]) + float(end["friction_work"]))
# measured 2026-12-02: -0.06 % (before the penalty was held at the smallest step: +4.6 %, the ringing
# contacts' pumped energy dissipated by the bulk viscosity)
rkcase.check(abs(absorbed / delivered - 1) < 0.01,
             f"delivered = internal + kinetic + friction of the part ({absorbed:.2f} J, {100 * (absorbed / delivered - 1):+.2f} %)")
exact = blow_reduction(delivered)
stroke = float(end["ram.stroke"])
x, _ = last_frame(one)
height = x[:, 2].max()
# measured 2026-12-02 at 2.5 mm: stroke +0.8 %, the part's top +1.4 % from the closed form (the
# stroke includes the contacts' penetrations; the top is the highest particle, at the rim)
for name, reduction in (("stroke", stroke / H0), ("part's height", 1 - height / H0)):
    rkcase.check(abs(reduction / exact - 1) < 0.03,
                 f"height reduction from the {name} {100 * reduction:.2f} %, energy balance of homogeneous upsetting "
                 f"{100 * exact:.2f} % ({100 * (reduction / exact - 1):+.2f} %)")

# the die's surface fields: the contact loads per triangle sum to the ram's force exactly (fixed point);
# the touched triangles cover the billet's end face (its radius from the part's top particles), whole
# triangles of the 2.5 mm die mesh: measured 2026-12-02 133.4 mm^2 against 112.1 mm^2 (1.19x); the
# filled fraction is that area over the die's working surface
def die_fields(case):
    m = meshio.read(sorted((case / "vtk").glob("die_ram_*.vtu"))[-1])
    x, tri = m.points, m.cells[0].data
    area = 0.5 * np.linalg.norm(np.cross(x[tri[:, 1]] - x[tri[:, 0]], x[tri[:, 2]] - x[tri[:, 0]]), axis=1)
    return area, {k: v[0].ravel() for k, v in m.cell_data.items()}


area, die = die_fields(one)
total = 4 * (die["contact_pressure"] * area).sum()
rkcase.check(abs(total / float(end["ram.force"]) - 1) < 1e-9,
             f"the die's contact pressure over its triangles sums to the ram's force ({total / 1e3:.4f} kN)")
touched = ((die["touched"] == 1) * area).sum()
working = ((die["touched"] >= 0) * area).sum()  # 0: untouched on the face toward the part; -1: off it
# the die's 20 x 20 mm face (x, y from -2 to 18 mm) reaching the modeled side of the symmetry planes:
# the 18 x 18 mm quarter and the triangles across its edges
rkcase.check(3.24e-4 <= working <= 4e-4, f"the die's working surface is its face toward the part within the modeled "
             f"quarter ({1e6 * working:.1f} mm^2)")
top = x[:, 2].max()
radius = np.hypot(x[x[:, 2] > top - 1e-4, 0], x[x[:, 2] > top - 1e-4, 1]).max()
face = math.pi * radius ** 2 / 4
rkcase.check(1.0 <= touched / face < 1.4 and abs(float(end["ram.filled"]) - touched / working) < 1e-6,
             f"touched {1e6 * touched:.1f} mm^2 of the die, the billet's end face {1e6 * face:.1f} mm^2; filled "
             f"{100 * float(end['ram.filled']):.2f} % of its working surface")
report = (one / "report.md").read_text()
rkcase.check(f"{100 * float(end['ram.filled']):.3g} % of its working surface filled" in report and "unfilled region" in report,
             "report.md gives the fill and the unfilled region: " + [l for l in report.splitlines() if "working surface" in l][0])

two_ranks = copy(prep2, "hammer_2")
tools.solve(two_ranks, 2)
tools.post(two_ranks)
a, b = last_frame(one), last_frame(two_ranks)
die2 = die_fields(two_ranks)[1]
rkcase.check(all(np.array_equal(p, q) for p, q in zip(a, b)) and rows(two_ranks)[-1]["ram.stroke"] == end["ram.stroke"]
             and all(np.array_equal(die[k], die2[k]) for k in die),
             "2 ranks: the ram's stroke, the last frame and the die's fields bitwise equal to 1 rank")

# a restart mid-blow: the run's last checkpoint removed, it goes on from the one before (step 30 000,
# the ram at 1.8 ms and 0.2 m/s) and must end bitwise equal
every = ["output.checkpoint_steps=10000"]
whole = copy(prep, "hammer_whole")
tools.solve(whole, 1, sets=every)
split = copy(whole, "hammer_split")
(split / "checkpoint" / "rank_0000.h5").unlink()
out = tools.run([tools.bin / "rksolve", split, "--quiet", "--restart", "--set", every[0]])
tools.post(whole)
tools.post(split)
c, w = last_frame(split), last_frame(whole)
rkcase.check(all(np.array_equal(p, q) for p, q in zip(w, c)) and rows(split)[-1]["ram.stroke"] == rows(whole)[-1]["ram.stroke"]
             and all(np.array_equal(p, q) for p, q in zip(a, w))
             and all(np.array_equal(die[k], die_fields(split)[1][k]) for k in die),
             "restarted mid-blow from step 30 000: the ram's stroke, the last frame and the die's fields (the "
             "touched triangles kept) bitwise equal (and the checkpoints change nothing)")

twice = copy(prep, "hammer_twice")
out = tools.solve(twice, 1, sets=["dies[0].motion.blow.energy=172", "dies[0].motion.blow.count=2"])
s2 = float(rows(twice)[-1]["ram.stroke"])
# measured 2026-12-02: equal to 5 digits (the second blow starts from the first one's rest: the same energy)
rkcase.check("stopped after 2 of 2 blows" in out.stderr and abs(s2 / stroke - 1) < 0.005,
             f"two blows of 172 J: stroke {1e3 * s2:.4f} mm against {1e3 * stroke:.4f} mm for one of 344 J")

# --- hydraulic press ---
F_LIM, M_RAM, SPEED = 150e3, 500.0, 0.1
hyd = tools.case("hydraulic")
tools.prep(hyd, 1, scene=GEO / "scene_hydraulic.yaml", sets=SPACING)
out = tools.solve(hyd, 1)
tools.post(hyd)
h = rows(hyd)
stall = float(h[-1]["ram.stroke"])
s_star = bisect(lambda s: force(s) - F_LIM, 0, 5e-3)  # the closed form reaches the limit
slope = (force(s_star + 1e-5) - force(s_star - 1e-5)) / 2e-5
s_end = bisect(lambda s: sum((force(s_star + (k + 0.5) * (s - s_star) / 200) - F_LIM) * (s - s_star) / 200
                             for k in range(200)) - 0.5 * M_RAM * SPEED ** 2, s_star, 5e-3)
# measured 2026-12-02 at 2.5 mm: +1.7 % (the billet's force there is 1-2 % above the closed form)
rkcase.check(float(h[-1]["time"]) < 0.05 and abs(stall / s_end - 1) < 0.03,
             f"stalls at {1e3 * stall:.3f} mm, short of its 5 mm: the energy balance of the ram gives {1e3 * s_end:.3f} mm "
             f"(the limit reached at {1e3 * s_star:.3f} mm) ({100 * (stall / s_end - 1):+.2f} %)")
peak = max(float(r["ram.force"]) for r in h)
overshoot = SPEED * math.sqrt(M_RAM * slope)
# measured 2026-12-02: 15.8 kN over the limit against v sqrt(M dF/ds) = 14.9 kN
rkcase.check(peak - F_LIM < 1.25 * overshoot,
             f"peak load {peak / 1e3:.1f} kN: {(peak - F_LIM) / 1e3:.1f} kN over the limit, the ram's inertia "
             f"{overshoot / 1e3:.1f} kN")
solve = json.load(open(hyd / "solve.json"))
report = (hyd / "report.md").read_text()
rkcase.check(any("stalled" in w for w in solve["warnings"]) and "stalled at stroke" in report,
             f"the stall is a warning in solve.json and report.md: {solve['warnings'][0]}")

reach = copy(hyd, "hydraulic_stroke")
out = tools.solve(reach, 1, sets=["dies[0].motion.hydraulic.force_limit=1e6", "dies[0].motion.hydraulic.stroke=1e-3"])
r = rows(reach)[-1]
rkcase.check(float(r["ram.stroke"]) == 1e-3 and "reached its stroke" in out.stderr and float(r["time"]) < 0.0125,
             f"a limit it never reaches: stops at its 1 mm stroke at {1e3 * float(r['time']):.2f} ms")

power = copy(hyd, "hydraulic_power")
tools.solve(power, 1, sets=["dies[0].motion.hydraulic.power_limit=5e3", "dies[0].motion.hydraulic.stroke=1.5e-3"])
p = rows(power)
most = max(float(x["ram.speed"]) * float(x["ram.force"]) for x in p)
# the speed of step n+1/2 is capped by the load at t^n; the history's speed is the step's mean: measured
# 2026-12-02 at most 5.011 kW
rkcase.check(most < 5e3 * 1.02 and float(p[-1]["ram.stroke"]) == 1.5e-3,
             f"a 5 kW power limit: speed x force at most {most / 1e3:.3f} kW, and it reaches its stroke")
# the same on 2 ranks: the ram's speed follows the fixed-point reaction summed over the ranks
power2 = tools.case("hydraulic_power_2")
tools.prep(power2, 2, scene=GEO / "scene_hydraulic.yaml", sets=SPACING)
tools.solve(power2, 2, sets=["dies[0].motion.hydraulic.power_limit=5e3", "dies[0].motion.hydraulic.stroke=1.5e-3"])
tools.post(power)
tools.post(power2)
ram = ("time", "ram.stroke", "ram.speed", "ram.force", "ram.delivered")
rkcase.check(all(np.array_equal(x, y) for x, y in zip(last_frame(power), last_frame(power2)))
             and [[r[k] for k in ram] for r in p] == [[r[k] for k in ram] for r in rows(power2)],
             "the hydraulic press on 2 ranks: every history row of the ram and the last frame bitwise equal to 1 rank")

low = copy(hyd, "hydraulic_low")
out = tools.solve(low, 1, sets=["dies[0].motion.hydraulic.force_limit=1e3"])
rkcase.check("stalled at stroke" in out.stderr and float(rows(low)[-1]["time"]) < 0.005,
             f"a force limit below the first contact's load: stalled at once, the run ends "
             f"({1e3 * float(rows(low)[-1]['time']):.2f} ms)")

# --- bad input ---
bad = tools.case("press_bad")
o = tools.prep(bad, 1, scene=GEO / "scene_hammer.yaml", sets=SPACING + ["dies[0].motion.blow.energy=0"], expect_ok=False)
rkcase.check(o.returncode != 0 and "energy" in o.stderr, f"a blow of no energy refused: {o.stderr.strip()}")
light = copy(prep, "hammer_light")
o = tools.solve(light, 1, sets=["dies[0].motion.blow.ram_mass=1e-4"], expect_ok=False)
rkcase.check(o.returncode != 0 and "too light" in o.stderr, f"a ram too light for the contact refused: {o.stderr.strip()}")
o = tools.prep(bad, 1, scene=GEO / "scene_hammer.yaml",
               sets=SPACING + ["boundaries.symmetry_planes[1].normal=[0, 0, 1]"], expect_ok=False)
rkcase.check(o.returncode != 0 and "across its motion" in o.stderr,
             f"a symmetry plane across the ram's motion refused: {o.stderr.strip()}")
