#!/usr/bin/python3
"""Curves of any case from CASE/history.csv: the energies against time with the energy error
(energies.png) and, for each moving die, the press force against its stroke (force_stroke.png).

  scripts/history_plots.py CASE        writes CASE/plots/energies.png [and force_stroke.png]"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_history(case: Path):
    with open(case / "history.csv") as f:
        return list(csv.DictReader(f))


def moving_dies(header):
    """Names of the dies in the history (a stroke and a press force column each)."""
    header = list(header)
    return [k[:-len(".stroke")] for k in header if k.endswith(".stroke") and k[:-len(".stroke")] + ".force" in header]


def plot_energies(rows, path: Path) -> None:
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


def plot_die_forces(rows, path: Path) -> bool:
    """Force against stroke of each moving die: raw (it rings with the stress waves) and a running
    mean over 2 % of the rows. False if no die moves."""
    fig, ax = plt.subplots(figsize=(6, 4))
    drawn = False
    for d in moving_dies(rows[0].keys()):
        stroke = [1e3 * float(r[d + ".stroke"]) for r in rows]
        if max(stroke) <= 0:
            continue
        force = np.array([1e-3 * float(r[d + ".force"]) for r in rows])
        k = max(1, len(rows) // 50)
        mean = np.convolve(force, np.ones(k) / k, mode="same")
        line, = ax.plot(stroke, force, alpha=0.3, lw=0.8)
        ax.plot(stroke[k // 2: len(stroke) - k // 2], mean[k // 2: len(stroke) - k // 2], color=line.get_color(),
                label=f"{d} (running mean)")
        drawn = True
    if drawn:
        ax.set_xlabel("stroke (mm)")
        ax.set_ylabel("press force, full part (kN)")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(path, dpi=120)
    plt.close(fig)
    return drawn


def main(case: Path) -> None:
    out = case / "plots"
    out.mkdir(exist_ok=True)
    rows = read_history(case)
    plot_energies(rows, out / "energies.png")
    written = ["energies.png"] + (["force_stroke.png"] if plot_die_forces(rows, out / "force_stroke.png") else [])
    print("plots:", ", ".join(f"{out}/{w}" for w in written))


if __name__ == "__main__":
    main(Path(sys.argv[1]))
