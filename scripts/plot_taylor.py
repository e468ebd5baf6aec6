#!/usr/bin/python3
"""Plots of a Taylor bar case: impact-face radius and length against time (like Fig. 7 of Wang et al.
2007, with that paper's final values marked) and the energy balance. Writes CASE/plots/*.png and
CASE/plots/results.json (the key results against the references, shown by rkpost in report.md)."""
import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from history_plots import plot_energies, pyplot, read_history  # noqa: E402
from case_check import case_folder, require_part  # noqa: E402
from taylor_metrics import HISTORY, HISTORY_US, REFERENCE, TAYLOR_PARTS, frames_of, metrics  # noqa: E402


def main(case: Path) -> None:
    out = case / "plots"
    out.mkdir(exist_ok=True)
    series = [metrics(case, k) for k in range(len(frames_of(case)))]
    t = [1e6 * m["time_s"] for m in series]
    plt = pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for a, key, label in ((ax[0], "footprint_radius_mm", "impact-face radius (mm)"),
                          (ax[1], "final_length_mm", "length (mm)")):
        a.plot(t, [m[key] for m in series], "o-", label="rkforge")
        a.plot(HISTORY_US, HISTORY[key], "k--", lw=1, label="converged FE history (composite tetrahedron, h = 0.19 mm)")
        a.plot([80], [REFERENCE[key]["converged"]], "*", ms=10, label="converged FE (80 us)")
        a.plot([80], [REFERENCE[key]["paper_rkpm"]], "s", label="2007 paper RKPM (80 us)")
        a.plot([80], [REFERENCE[key]["paper_fem"]], "^", label="2007 paper FEM, LS-DYNA (80 us)")
        a.set_xlabel("time (us)")
        a.set_ylabel(label)
        a.grid(True)
        a.legend(fontsize=8)
    fig.suptitle(f"Taylor bar, {series[-1]['particles']} particles")
    fig.tight_layout()
    fig.savefig(out / "taylor_radius_length.png", dpi=110)

    plot_energies(read_history(case), out / "energies.png")

    # key results against the published ones, for CASE/report.md (rkpost reads plots/results.json)
    last = series[-1]
    results = [{"quantity": label, "value": round(last[key], 3), "unit": "mm", "reference": REFERENCE[key]["converged"],
                "source": "converged FE at 80 us (Foulk et al. 2021)"}
               for key, label in (("footprint_radius_mm", "footprint radius (impact face)"), ("final_length_mm", "final length"))]
    results.append({"quantity": "rim lifted off the wall", "value": round(last["rim_lift_mm"], 3), "unit": "mm",
                    "reference": None, "source": "-"})
    results.append({"quantity": "peak eq. plastic strain", "value": round(last["max_eq_plastic_strain"], 3), "unit": "-",
                    "reference": None, "source": "other codes 2.5-3.2"})
    (out / "results.json").write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", type=case_folder(("prep.json", "history.csv", "vtk/case.pvd")))
    a = ap.parse_args()
    require_part(a.case, TAYLOR_PARTS, "Taylor bar (geometry/taylor_bar)")
    main(a.case)
