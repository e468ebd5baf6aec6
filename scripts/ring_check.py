#!/usr/bin/python3
"""Ring compression (geometry/ring_compression): the ring's height and bore from the last frame that
rkpost wrote, read with meshio. The bore is the mean current distance from the axis of the particles
that were on the inner surface (r = 7.5 mm) at the ring's mid-height (z = 0) at t = 0, where friction
makes it narrowest; the outer diameter the largest among those on the outer surface; the height
twice the largest z. The frictionless ring deforms homogeneously: its
bore grows to 7.5 mm sqrt(H0 / H). Usage:
  ring_check.py CASE [--json]
"""
import math
from pathlib import Path

import meshio
import numpy as np

from case_check import main_of


def check(case: Path) -> dict:
    frames = sorted((case / "vtk").glob("frame_*.vtu"))
    m = meshio.read(frames[-1])
    x = m.points
    X = x - m.point_data["displacement"]
    R0 = np.hypot(X[:, 0], X[:, 1])
    r = np.hypot(x[:, 0], x[:, 1])
    inner, outer = (np.abs(R0 - 7.5e-3) < 1e-6) & (np.abs(X[:, 2]) < 1e-6), np.abs(R0 - 15e-3) < 1e-6
    height = 2 * x[:, 2].max()
    out = {"height_mm": 1e3 * height, "reduction": 1 - height / 10e-3, "inner_diameter_mm": 2e3 * r[inner].mean(),
           "outer_diameter_mm": 2e3 * r[outer].max(),
           "frictionless_inner_diameter_mm": 15 * math.sqrt(10e-3 / height)}
    out["inner_diameter_change"] = out["inner_diameter_mm"] / 15 - 1
    return out


def summary(r: dict) -> str:
    return " ".join(f"{k}={v:.4f}" for k, v in r.items())


if __name__ == "__main__":
    main_of(__doc__, check, summary, needs=("vtk/case.pvd",), parts=("ring.geo",), what="ring compression (geometry/ring_compression)")
