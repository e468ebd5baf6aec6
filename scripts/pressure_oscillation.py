#!/usr/bin/python3
"""Point-to-point oscillation of the pressure at a case's last frame: at each particle, its pressure
less the mean of its neighbours' (particles within 1.5 spacings at t = 0). A smooth field leaves only
its curvature; a checkerboard (pressure modes of a nearly incompressible material) shows as the
RMS of that difference. Usage:
  pressure_oscillation.py CASE [--json]
"""

import meshio
import numpy as np

from case_check import main_of
from taylor_metrics import frames_of, spacing_of


def check(case) -> dict:
    time, path = frames_of(case)[-1]
    mesh = meshio.read(path)
    x = np.asarray(mesh.points)
    X = x - np.asarray(mesh.point_data["displacement"])
    p = np.asarray(mesh.point_data["pressure"]).ravel()
    reach2 = (1.5 * spacing_of(case)) ** 2
    d = np.empty(len(p))
    for lo in range(0, len(p), 512):  # neighbour means, a block of particles at a time
        hi = min(lo + 512, len(p))
        near = ((X[lo:hi, None, :] - X[None, :, :]) ** 2).sum(axis=2) <= reach2
        near[np.arange(hi - lo), np.arange(lo, hi)] = False
        d[lo:hi] = p[lo:hi] - (near @ p) / np.maximum(near.sum(axis=1), 1)
    return {"time_s": time, "particles": int(len(p)), "pressure_rms_gpa": float(np.sqrt(np.mean(p ** 2))) / 1e9,
            "oscillation_rms_gpa": float(np.sqrt(np.mean(d ** 2))) / 1e9,
            "oscillation_p99_gpa": float(np.percentile(np.abs(d), 99)) / 1e9}


def summary(r: dict) -> str:
    return (f"pressure at {1e6 * r['time_s']:.1f} us ({r['particles']} particles): RMS {r['pressure_rms_gpa']:.3f} GPa, "
            f"point-to-point oscillation RMS {r['oscillation_rms_gpa']:.3f} GPa (99th percentile {r['oscillation_p99_gpa']:.3f} GPa)")


if __name__ == "__main__":
    main_of(__doc__, check, summary, needs=("prep.json", "vtk/case.pvd"))
