#!/usr/bin/python3
"""Forming results of a case with dies (back extrusion, wheel forging, upsetting): the numbers that
decide a press and a die design, and the pictures that show them.

  forming_report.py CASE [--json] [--stages N]

Reads CASE/history.csv (die stroke and force, energies, volume change) and CASE/vtk/case.pvd (the
merged frames from rkpost: workpiece = part 0, dies = parts 1, 2, ...). Writes
  CASE/plots/force_stroke.png   press force (full part) against stroke, one curve per moving die
  CASE/plots/energies.png       energy balance against time
  CASE/plots/stages.png         sections through the first symmetry plane at N stages (like
                                Figs. 11 and 16 of Wang et al. 2007): particles coloured by plastic strain, dies grey
and prints (or --json) the stroke reached, peak force, energy error and volume change: the points'
(sum w_g J, elastic by construction), and the cells' through the particles less the points' (what the
discretization lost or gained).
"""
import argparse
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from case_check import case_folder  # noqa: E402
from history_plots import moving_dies, plot_die_forces, plot_energies, pyplot, read_history  # noqa: E402


def summary(case: Path) -> dict:
    rows = read_history(case)
    late = rows[len(rows) // 10:]  # after the start-up, where the energies are still tiny
    out = {"time_s": float(rows[-1]["time"]), "steps_rows": len(rows),
           "max_energy_error": max(float(r["energy_error"]) for r in late),
           "final_energy_error": float(rows[-1]["energy_error"]),
           "max_abs_volume_change": None, "final_volume_change": None,
           "friction_work_J": float(rows[-1]["friction_work"]),
           "max_penetration_mm": 1e3 * max(float(r["max_penetration"]) for r in rows),
           "external_work_J": float(rows[-1]["contact_work"]), "dies": {}}
    for d in moving_dies(rows[0].keys()):
        stroke = np.array([float(r[d + ".stroke"]) for r in rows])
        force = np.array([float(r[d + ".force"]) for r in rows])
        out["dies"][d] = {"stroke_mm": 1e3 * stroke[-1], "peak_force_kN": 1e-3 * force.max(),
                          "final_force_kN": 1e-3 * force[-1], "work_J": float(rows[-1][d + ".work"])}
    if "volume_change" in rows[0]:  # (histories written before the column existed lack it)
        out["max_abs_volume_change"] = max(abs(float(r["volume_change"])) for r in rows)
        out["final_volume_change"] = float(rows[-1]["volume_change"])
    # Plastic flow keeps the volume; the elastic part follows the pressure: dV/V = -p/K. The mean
    # particle pressure of the last frame gives the elastic share, the rest is the method's error.
    material = yaml.safe_load((case / "scene.resolved.yaml").read_text())["material"]
    K = material["youngs_modulus"] / (3 * (1 - 2 * material["poisson_ratio"]))
    last = meshio.read(frames(case)[-1][1])
    out["mean_pressure_MPa"] = float(np.mean(last.point_data["pressure"])) / 1e6
    out["elastic_volume_change"] = -1e6 * out["mean_pressure_MPa"] / K
    if out["final_volume_change"] is not None:
        out["nonelastic_volume_change"] = out["final_volume_change"] - out["elastic_volume_change"]
    # The points' volume (sum w_g J, volume_change) is elastic by construction: the return map keeps
    # det F_p = 1. What the discretization loses or gains shows in the picture: the volume of the
    # cells through the particles where the material is, each frame against the first, less the points'
    # change at the frame's time.
    times = np.array([float(r["time"]) for r in rows])
    cells = []
    all_frames = frames(case)
    V0 = cells_volume(meshio.read(all_frames[0][1]))
    for t, w, _ in all_frames[1:]:
        change = cells_volume(meshio.read(w)) / V0 - 1
        points = float(rows[int(np.argmin(np.abs(times - t)))]["volume_change"]) if out["final_volume_change"] is not None else 0.0
        cells.append((t, change, change - points))
    if cells:
        out["final_cells_volume_change"] = cells[-1][1]
        out["cells_less_points"] = [{"time_s": t, "cells": c, "less_points": d} for t, c, d in cells]
        out["max_abs_cells_less_points"] = max(abs(d) for _, _, d in cells)
    return out


# Hexahedra as 6 tetrahedra about the 0-6 diagonal (the trilinear volume for planar faces).
HEX_TETS = ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6))


def cells_volume(mesh) -> float:
    x, volume = np.asarray(mesh.points), 0.0
    for block in mesh.cells:
        tets = HEX_TETS if block.type == "hexahedron" else ((0, 1, 2, 3),) if block.type == "tetra" else ()
        for t in tets:
            a, b, c, d = (x[block.data[:, i]] for i in t)
            volume += float(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)).sum()) / 6
    return volume


def frames(case: Path):
    """[(time, workpiece .vtu, [die .vtu, ...])] from the .pvd."""
    by_time = {}
    for d in ET.parse(case / "vtk" / "case.pvd").getroot().iter("DataSet"):
        entry = by_time.setdefault(float(d.get("timestep")), [None, []])
        path = case / "vtk" / d.get("file")
        if d.get("part", "0") == "0":
            entry[0] = path
        else:
            entry[1].append(path)
    return [(t, w, dies) for t, (w, dies) in sorted(by_time.items()) if w is not None]


def first_plane(case: Path):
    """Point and unit normal of the first symmetry plane in scene.resolved.yaml, else y = 0."""
    scene = yaml.safe_load((case / "scene.resolved.yaml").read_text())
    planes = (scene.get("boundaries") or {}).get("symmetry_planes") or []
    if not planes:
        return np.zeros(3), np.array([0.0, 1.0, 0.0])
    normal = np.array(planes[0]["normal"], dtype=float)
    return np.array(planes[0]["point"], dtype=float), normal / np.linalg.norm(normal)


def section(points, triangles, point, normal):
    """Segments where the plane cuts the triangles."""
    d = (points - point) @ normal
    segs = []
    for tri in triangles:
        dd = d[tri]
        if dd.min() > 0 or dd.max() < 0:
            continue
        cut = []
        for a, b in ((0, 1), (1, 2), (2, 0)):
            da, db = dd[a], dd[b]
            if (da <= 0 < db) or (db <= 0 < da):
                s = da / (da - db)
                cut.append(points[tri[a]] + s * (points[tri[b]] - points[tri[a]]))
        if len(cut) == 2:
            segs.append(cut)
    return segs


def plots(case: Path, stages: int) -> None:
    out = case / "plots"
    out.mkdir(exist_ok=True)
    rows = read_history(case)
    plot_die_forces(rows, out / "force_stroke.png")
    plot_energies(rows, out / "energies.png")

    all_frames = frames(case)
    picks = sorted({round(k * (len(all_frames) - 1) / max(stages - 1, 1)) for k in range(stages)})
    point, normal = first_plane(case)
    plt = pyplot()
    fig, axes = plt.subplots(1, len(picks), figsize=(3.2 * len(picks), 4), sharey=True)
    axes = np.atleast_1d(axes)
    spacing = None
    last = meshio.read(all_frames[picks[-1]][1]).point_data["eq_plastic_strain"].ravel()
    vmax = max(float(last.max()), 1e-3)  # one colour scale for all stages
    for a, k in zip(axes, picks):
        t, wpath, dpaths = all_frames[k]
        m = meshio.read(wpath)
        x = np.asarray(m.points)
        if spacing is None:
            spacing = np.median(np.linalg.norm(x[1:] - x[:-1], axis=1))
        near = np.abs((x - point) @ normal) < 0.3 * spacing
        r = np.hypot(x[near, 0], x[near, 1])
        sc = a.scatter(1e3 * r, 1e3 * x[near, 2], c=m.point_data["eq_plastic_strain"].ravel()[near], s=10,
                       cmap="viridis", vmin=0, vmax=vmax)
        for dp in dpaths:
            dm = meshio.read(dp)
            tris = next((c.data for c in dm.cells if c.type == "triangle"), None)
            if tris is None:
                continue
            for s0, s1 in section(np.asarray(dm.points), tris, point, normal):
                a.plot(1e3 * np.hypot([s0[0], s1[0]], [s0[1], s1[1]]), 1e3 * np.array([s0[2], s1[2]]),
                       color="0.5", lw=0.8)
        a.set_title(f"t = {1e3 * t:.3g} ms")
        a.set_xlabel("r (mm)")
        a.set_aspect("equal")
    axes[0].set_ylabel("z (mm)")
    fig.colorbar(sc, ax=list(axes), shrink=0.7, label="equivalent plastic strain")
    fig.savefig(out / "stages.png", dpi=120, bbox_inches="tight")
    plt.close(fig)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.splitlines()[2:]))
    ap.add_argument("case", type=case_folder(("prep.json", "history.csv", "vtk/case.pvd")))
    ap.add_argument("--stages", type=int, default=4, help="sections drawn in stages.png (default 4)")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    case = a.case
    if not moving_dies(read_history(case)[0].keys()):
        raise SystemExit(f"forming_report.py: {case}: no die moves in this case (a forming report needs a press)")
    res = summary(case)
    plots(case, max(a.stages, 1))
    if a.json:
        print(json.dumps(res, indent=2))
    else:
        volume = ("not recorded" if res["final_volume_change"] is None else
                  f"{100 * res['final_volume_change']:+.3f} % (max |.| {100 * res['max_abs_volume_change']:.3f} %; "
                  f"elastic under the mean pressure {res['mean_pressure_MPa']:.0f} MPa: "
                  f"{100 * res['elastic_volume_change']:+.3f} %, the rest {100 * res['nonelastic_volume_change']:+.3f} %)")
        print(f"{case}: t = {1e3 * res['time_s']:.4g} ms, energy error {100 * res['final_energy_error']:.3f} % at the end, "
              f"{100 * res['max_energy_error']:.3f} % at most after 10 % of the run, volume change {volume}")
        if "final_cells_volume_change" in res:
            print(f"  cells through the particles: volume {100 * res['final_cells_volume_change']:+.3f} % at the end; "
                  f"less the points' change {100 * res['cells_less_points'][-1]['less_points']:+.3f} % "
                  f"(max |.| over the frames {100 * res['max_abs_cells_less_points']:.3f} %)")
        print(f"  deepest particle in a die during the run: {res['max_penetration_mm']:.4f} mm")
        for d, v in res["dies"].items():
            if v["stroke_mm"] > 0:
                print(f"  {d}: stroke {v['stroke_mm']:.3f} mm, force {v['final_force_kN']:.1f} kN at the end, "
                      f"peak {v['peak_force_kN']:.1f} kN, work {v['work_J']:.1f} J (modeled part)")
        print(f"  plots: {case / 'plots'}/force_stroke.png, energies.png, stages.png")
