#!/usr/bin/python3
"""Curves of any case from CASE/history.csv: the energies against time with the energy error
(energies.png) and, for each moving die, the press force against its stroke (force_stroke.png).

  scripts/history_plots.py CASE        writes CASE/plots/energies.png [and force_stroke.png]
  scripts/history_plots.py --compare OUT.png CASE[=LABEL] ...
                                       one die's running-mean force against stroke for several
                                       cases (a resolution study), the first moving die of each"""
import argparse
import csv
from pathlib import Path

import numpy as np

from case_check import check_run


def pyplot():
    """matplotlib's pyplot, drawing off-screen; imported when a plot is drawn, not with the module: its
    half second a run would weigh on every --help, every error and every script run that draws nothing
    (the studies' plans and runs, the scripts' reads)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def read_history(case: Path):
    with open(case / "history.csv") as f:
        return list(csv.DictReader(f))


def moving_dies(header):
    """Names of the dies in the history (a stroke and a press force column each)."""
    header = list(header)
    return [k[:-len(".stroke")] for k in header if k.endswith(".stroke") and k[:-len(".stroke")] + ".force" in header]


def plot_energies(rows, path: Path) -> None:
    plt = pyplot()
    end = float(rows[-1]["time"])
    scale, unit = (1e6, "us") if end < 1e-3 else (1e3, "ms") if end < 1 else (1.0, "s")
    t = [scale * float(r["time"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    for key in ("kinetic", "internal", "plastic_work", "external_work", "contact_work", "friction_work"):
        values = [float(r[key]) for r in rows]
        if max(map(abs, values)) > 0:
            ax.plot(t, values, label=key)
    ax.set_xlabel(f"time ({unit})")
    ax.set_ylabel("energy of the modeled part (J)")
    ax.grid(alpha=0.3)
    ax2 = ax.twinx()
    ax2.plot(t, [100 * float(r["energy_error"]) for r in rows], "k:", label="energy error (%)")
    ax2.set_ylabel("energy error (%)")
    lines = ax.get_legend_handles_labels()
    more = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], fontsize=8, loc="center right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def force_curve(rows, die):
    """Stroke (mm), force (kN) and its running mean over 2 % of the rows (the force rings with the
    stress waves), the mean's ends cut where its window is incomplete; None if the die does not move."""
    stroke = np.array([1e3 * float(r[die + ".stroke"]) for r in rows])
    if stroke.max() <= 0:
        return None
    force = np.array([1e-3 * float(r[die + ".force"]) for r in rows])
    k = max(1, len(rows) // 50)
    mean = np.convolve(force, np.ones(k) / k, mode="same")
    cut = slice(k // 2, len(stroke) - k // 2)
    return stroke, force, stroke[cut], mean[cut]


def finish_force_plot(fig, ax, path: Path) -> None:
    ax.set_xlabel("stroke (mm)")
    ax.set_ylabel("press force, full part (kN)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_die_forces(rows, path: Path) -> bool:
    """Force against stroke of each moving die, raw and its running mean. False if no die moves."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    drawn = False
    for d in moving_dies(rows[0].keys()):
        curve = force_curve(rows, d)
        if curve is None:
            continue
        line, = ax.plot(curve[0], curve[1], alpha=0.3, lw=0.8)
        ax.plot(curve[2], curve[3], color=line.get_color(), label=f"{d} (running mean)")
        drawn = True
    if drawn:
        finish_force_plot(fig, ax, path)
    plt.close(fig)
    return drawn


def compare_forces(out: Path, cases) -> None:
    """The running-mean force of each case's first moving die, on one plot."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for spec in cases:
        case, _, label = spec.partition("=")
        rows = read_history(Path(case))
        curve = next((c for c in (force_curve(rows, d) for d in moving_dies(rows[0].keys())) if c is not None), None)
        if curve is None:
            raise SystemExit(f"history_plots.py: {case}/history.csv: no die moves")
        ax.plot(curve[2], curve[3], label=label or case)
    finish_force_plot(fig, ax, out)
    plt.close(fig)
    print("plot:", out)


def main(case: Path) -> None:
    out = case / "plots"
    out.mkdir(exist_ok=True)
    rows = read_history(case)
    plot_energies(rows, out / "energies.png")
    written = ["energies.png"] + (["force_stroke.png"] if plot_die_forces(rows, out / "force_stroke.png") else [])
    print("plots:", ", ".join(f"{out}/{w}" for w in written))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.splitlines()[2:]))
    ap.add_argument("case", nargs="*", help="CASE, or with --compare CASE[=LABEL] ...")
    ap.add_argument("--compare", type=Path, metavar="OUT.png", help="one die's force against stroke for several cases")
    a = ap.parse_args()
    if not a.case:
        ap.error("a CASE folder is needed")
    for spec in a.case:
        case = spec.partition("=")[0] if a.compare else spec
        if not (Path(case) / "history.csv").exists():
            ap.error(f"{case}: not a case folder with history.csv (written by rksolve)")
        check_run(Path(case))
    if a.compare:
        compare_forces(a.compare, a.case)
    elif len(a.case) > 1:
        ap.error("one CASE (several: --compare OUT.png CASE ...)")
    else:
        main(Path(a.case[0]))
