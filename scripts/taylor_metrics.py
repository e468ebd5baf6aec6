#!/usr/bin/python3
"""Taylor bar metrics from the .vtu files that rkpost wrote (BENCHMARKS.md case 1).

r_f: the largest distance from the bar axis among the particles within 0.3 spacing of the wall
plane (the minimum coordinate along the axis); L_f: the extent along the axis. Read with meshio,
independently of the solver. Usage:
  taylor_metrics.py CASE [--frame N] [--axis z] [--json]
"""
import argparse
import json
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np

PUBLISHED = {  # seed Table/section 5.1 and BENCHMARKS.md
    "footprint_radius_mm": {"seed_rkpm": 7.30, "seed_fem": 7.38, "band": [6.86, 7.36]},
    "final_length_mm": {"seed_rkpm": 21.48, "seed_fem": 21.46, "band": [21.15, 21.75]},
}


def spacing_of(case: Path) -> float:
    text = (case / "scene.resolved.yaml").read_text()
    return float(re.search(r"^\s*spacing:\s*([0-9.eE+-]+)", text, re.M).group(1))


def frames_of(case: Path):
    root = ET.parse(case / "vtk" / "case.pvd").getroot()
    return [(float(d.get("timestep")), case / "vtk" / d.get("file")) for d in root.iter("DataSet")
            if d.get("part", "0") == "0"]  # part 0 is the workpiece; the dies are parts 1, 2, ...


def metrics(case: Path, frame: int = -1, axis: int = 2) -> dict:
    time, path = frames_of(case)[frame]
    mesh = meshio.read(path)
    x = np.asarray(mesh.points)
    h = spacing_of(case)
    z = x[:, axis]
    radial = np.delete(x, axis, axis=1)
    wall = z.min()
    near = np.abs(z - wall) <= 0.3 * h
    r = np.sqrt((radial ** 2).sum(axis=1))
    data = mesh.point_data
    return {
        "time_s": time,
        "particles": int(len(x)),
        "footprint_radius_mm": 1e3 * float(r[near].max()),
        # resolution-independent companions: the rim curls off the wall, so "on the wall" (0.3 h) reads a
        # smaller radius as h falls; the radius within fixed heights of the wall, and the largest radius
        **{f"radius_{d:g}mm_mm": 1e3 * float(r[z - wall <= d * 1e-3].max()) for d in (0.1, 0.2)},
        "max_radius_mm": 1e3 * float(r.max()),
        "final_length_mm": 1e3 * float(z.max() - wall),
        "max_eq_plastic_strain": float(np.max(data["eq_plastic_strain"])),
        "finite": bool(all(np.isfinite(np.asarray(v)).all() for v in data.values()) and np.isfinite(x).all()),
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", type=Path)
    ap.add_argument("--frame", type=int, default=-1)
    ap.add_argument("--axis", default="z", choices="xyz")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    m = metrics(a.case, a.frame, "xyz".index(a.axis))
    if a.json:
        print(json.dumps(m, indent=2))
        return 0
    print(f"Taylor bar at t = {1e6 * m['time_s']:.1f} us, {m['particles']} particles")
    for key, label in (("footprint_radius_mm", "footprint radius"), ("final_length_mm", "final length")):
        p = PUBLISHED[key]
        lo, hi = p["band"]
        verdict = "inside" if lo <= m[key] <= hi else "OUTSIDE"
        print(f"  {label:17s} {m[key]:7.3f} mm   seed RKPM {p['seed_rkpm']:.2f}, seed FEM {p['seed_fem']:.2f},"
              f" band {lo}-{hi} mm ({verdict})")
    print(f"  max eq. plastic strain {m['max_eq_plastic_strain']:.2f} (other codes 2.5-3.2)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
