#!/usr/bin/python3
"""The Taylor bar of Wang et al. 2007 in CalculiX (ccx explicit dynamics), for the bench's side-by-side.

Wang, Li, Han & Zhong (Development of parallel 3D RKPM meshless bulk forming simulation system,
2007, section 5.1) compared their RKPM bar with LS-DYNA on 1200 hexahedra; this runs the same quarter bar
(radius 3.2 mm, length 32.4 mm, OFHC copper of the paper's Table 1, 227 m/s onto a rigid frictionless
wall, 80 us) on 1200 reduced-integration hexahedra (C3D8R) in an independent finite-element
code, Debian's calculix-ccx (installed with apt when missing). The wall is the impact face held
at u_z = 0 (frictionless: the face slides freely in its plane; the bar does not rebound within
80 us), the quarter's cut faces are symmetry planes. Writes CASE/taylor.inp, runs ccx there and
prints one JSON object: wall time, footprint radius and final length (measured as for rkforge
by scripts/taylor_metrics.py: the largest radius among the nodes on the wall, the extent along the axis).
  scripts/calculix_taylor.py --work CASE [--layers 25 --square 4]
"""
import argparse
import json
import math
import shutil
import subprocess
import time
from pathlib import Path

R, L, V = 3.2e-3, 32.4e-3, 227.0
E, NU, RHO, SY, H = 117.0e9, 0.35, 8930.0, 400.0e6, 100.0e6  # Table 1 of Wang et al. 2007 (as geometry/taylor_bar)


def ensure_ccx():
    if shutil.which("ccx"):
        return
    apt = ["apt-get", "install", "-y", "-q", "calculix-ccx"]
    if subprocess.run(apt, stdout=subprocess.DEVNULL).returncode != 0:  # a fresh machine has no lists
        subprocess.run(["apt-get", "update", "-q"], check=True, stdout=subprocess.DEVNULL)
        subprocess.run(apt, check=True, stdout=subprocess.DEVNULL)


def quarter_section(n):
    """Structured O-grid of the quarter disc: an n x n inner square and two n x n outer blocks.
    Returns the 2D nodes (list of (x, y)) and the quads (4 node indices, counter-clockwise)."""
    a = 0.5 * R  # the inner square's side
    nodes, index = [], {}

    def node(key, xy):
        if key not in index:
            index[key] = len(nodes)
            nodes.append(xy)
        return index[key]

    def square(i, j):  # inner square, i, j in 0..n
        return node(("s", i, j), (a * i / n, a * j / n))

    def outer(block, i, k):  # block 0 spans the square's edge x = a, block 1 the edge y = a; k: radial
        s = i / n  # along the edge, 0 at the axis, 1 at the corner
        if k == 0:
            return square(n, i) if block == 0 else square(i, n)
        edge = (a, a * s) if block == 0 else (a * s, a)
        phi = (math.pi / 4) * s if block == 0 else math.pi / 2 - (math.pi / 4) * s
        arc = (R * math.cos(phi), R * math.sin(phi))
        t = k / n
        key = ("o", block, i, k) if i < n else ("c", k)  # the corner line is shared by both blocks
        return node(key, (edge[0] + t * (arc[0] - edge[0]), edge[1] + t * (arc[1] - edge[1])))

    quads = []
    for i in range(n):
        for j in range(n):
            quads.append((square(i, j), square(i + 1, j), square(i + 1, j + 1), square(i, j + 1)))
    for i in range(n):
        for k in range(n):
            quads.append((outer(0, i, k), outer(0, i, k + 1), outer(0, i + 1, k + 1), outer(0, i + 1, k)))
            quads.append((outer(1, i, k), outer(1, i + 1, k), outer(1, i + 1, k + 1), outer(1, i, k + 1)))
    return nodes, quads


def layer_heights(layers, first):
    """z of the layer interfaces, thickness growing geometrically from `first` at the impact face
    (the mushroom needs the fine layers there; the far end stays nearly rigid)."""
    lo, hi = 1.0, 2.0
    for _ in range(200):  # the ratio q with first (q^layers - 1) / (q - 1) = L, by bisection
        q = 0.5 * (lo + hi)
        lo, hi = (q, hi) if first * (q ** layers - 1) / (q - 1) < L else (lo, q)
    z = [0.0]
    for k in range(layers):
        z.append(z[-1] + first * q ** k)
    return [L * zk / z[-1] for zk in z]


def write_deck(path, layers, n, first_layer):
    section, quads = quarter_section(n)
    ns = len(section)
    heights = layer_heights(layers, first_layer)
    lines = ["*HEADING", "Taylor bar, Wang et al. 2007 section 5.1: quarter model, C3D8R", "*NODE, NSET=NALL"]
    for layer in range(layers + 1):
        z = heights[layer]
        for i, (x, y) in enumerate(section):
            lines.append(f"{layer * ns + i + 1}, {x:.9e}, {y:.9e}, {z:.9e}")
    lines.append("*ELEMENT, TYPE=C3D8R, ELSET=EALL")
    e = 0
    for layer in range(layers):
        for q in quads:
            e += 1
            bottom = [layer * ns + v + 1 for v in q]
            top = [(layer + 1) * ns + v + 1 for v in q]
            lines.append(f"{e}, " + ", ".join(str(v) for v in bottom + top))
    sets = {"NX0": [i for i, (x, _) in enumerate(section) if abs(x) < 1e-12],
            "NY0": [i for i, (_, y) in enumerate(section) if abs(y) < 1e-12]}
    for name, ids in sets.items():
        lines.append(f"*NSET, NSET={name}")
        lines += [f"{layer * ns + i + 1}," for layer in range(layers + 1) for i in ids]
    lines.append("*NSET, NSET=NWALL")
    lines += [f"{i + 1}," for i in range(ns)]
    lines += ["*MATERIAL, NAME=COPPER", "*ELASTIC", f"{E:.6e}, {NU}", "*DENSITY", f"{RHO}",
              "*PLASTIC", f"{SY:.6e}, 0.0", f"{SY + H * 10:.6e}, 10.0",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=COPPER",
              "*INITIAL CONDITIONS, TYPE=VELOCITY", f"NALL, 3, {-V}",
              "*BOUNDARY", "NX0, 1, 1", "NY0, 2, 2", "NWALL, 3, 3",
              "*STEP, NLGEOM, INC=10000000", "*DYNAMIC, EXPLICIT", "1.0e-8, 80.0e-6",
              "*NODE PRINT, NSET=NALL, FREQUENCY=10000000", "U", "*END STEP"]
    path.write_text("\n".join(lines) + "\n")
    return e, heights, section


def final_displacements(dat):
    """The last block of node displacements in the .dat file: {node: (ux, uy, uz)}."""
    blocks, current = [], None
    for line in dat.read_text().splitlines():
        if line.strip().startswith("displacements"):
            current = {}
            blocks.append(current)
            continue
        parts = line.split()
        if current is not None and len(parts) == 4:
            try:
                current[int(parts[0])] = tuple(float(p) for p in parts[1:])
            except ValueError:
                pass
    if not blocks or not blocks[-1]:
        raise SystemExit(f"calculix_taylor: no displacements in {dat}")
    return blocks[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", type=Path, required=True)
    ap.add_argument("--layers", type=int, default=25)  # 25 layers x 48 hexahedra = 1200
    ap.add_argument("--square", type=int, default=4)   # the section: 4 x 4 + 2 x 4 x 4 = 48 quads
    ap.add_argument("--first-layer", type=float, default=0.8)  # mm, the layer on the wall
    a = ap.parse_args()
    ensure_ccx()
    a.work.mkdir(parents=True, exist_ok=True)
    elements, heights, section = write_deck(a.work / "taylor.inp", a.layers, a.square, 1e-3 * a.first_layer)
    t0 = time.perf_counter()
    run = subprocess.run(["ccx", "-i", "taylor"], cwd=a.work, capture_output=True, text=True,
                         env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
    wall = time.perf_counter() - t0
    (a.work / "ccx.log").write_text(run.stdout + run.stderr)
    if run.returncode != 0 or "*ERROR" in run.stdout:
        raise SystemExit(f"calculix_taylor: ccx failed, see {a.work / 'ccx.log'}")
    u = final_displacements(a.work / "taylor.dat")
    if not all(math.isfinite(c) for d in u.values() for c in d):
        raise SystemExit(f"calculix_taylor: ccx's displacements are not finite (its fixed explicit step was "
                         f"unstable for this mesh; thicken --first-layer), see {a.work / 'taylor.dat'}")
    ns = len(section)
    radius = max(math.hypot(section[i][0] + u[i + 1][0], section[i][1] + u[i + 1][1]) for i in range(ns))
    length = max(heights[k // ns] + u[k + 1][2] for k in range(len(heights) * ns))
    out = {"code": "CalculiX ccx 2.20 (explicit, C3D8R, NLGEOM)", "elements": elements, "nodes": len(heights) * ns,
           "wall_s": wall, "r_f_mm": 1e3 * radius, "L_f_mm": 1e3 * length}
    (a.work / "calculix.json").write_text(json.dumps(out, indent=2) + "\n")
    print(json.dumps(out))


if __name__ == "__main__":
    main()
