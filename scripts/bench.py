#!/usr/bin/python3
"""make bench: strong scaling of a large Taylor bar (>= 100k particles) over MPI ranks.

Prepares the case once per rank count (reused when present), runs a fixed simulated time, and
reports wall time, speedup and efficiency against the seed's Table 2, time in communication per
step, and the partition report. Timings are ratios within one run on one machine.
  scripts/bench.py --bin build/bin --work build/bench [--ranks 1 2] [--spacing 0.18e-3] [--end 1e-6]
"""
import argparse
import json
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SEED_SPEEDUP = {1: 1.00, 2: 1.81, 4: 3.21, 8: 6.41, 16: 10.39, 32: 24.14}  # seed Table 2 (Taylor bar)
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def run(args):
    subprocess.run([str(a) for a in args], check=True, env=ENV)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", type=Path, default=ROOT / "build" / "bin")
    ap.add_argument("--work", type=Path, default=ROOT / "build" / "bench")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--spacing", default="0.18e-3")
    ap.add_argument("--end", default="1e-6")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    scene = ROOT / "geometry" / "taylor_bar" / "scene.yaml"
    rows = []
    for n in a.ranks:
        case = a.work / f"taylor_{a.spacing}_r{n}"
        run([a.bin / "rkprep", scene, "--ranks", n, "--out", case, "--quiet",  # always: a case left by an
             "--set", f"discretization.spacing={a.spacing}"])                 # older build may not read
        run(["mpirun", "-np", n, a.bin / "rksolve", case, "--quiet", "--set", f"time.end={a.end}",
             "--set", f"time.output_interval={a.end}"])
        prep = json.loads((case / "prep.json").read_text())
        solve = json.loads((case / "solve.json").read_text())
        loop = solve["wall_s"] - solve["setup_s"]
        ph = solve["phases"]
        comm = ph["overlap_exchange"]["max_s"] + ph["time_step"]["max_s"] - ph["time_step"]["min_s"]
        rows.append({"ranks": n, "particles": prep["particles"], "points": prep["integration_points"],
                     "steps": solve["steps"], "loop_s": loop, "setup_s": solve["setup_s"], "prep_s": prep["wall_s"],
                     "comm_ms_per_step": 1e3 * comm / max(solve["steps"], 1),
                     "ns_per_point_update": solve["ns_per_point_update"],
                     "neighbours_per_point": solve["neighbours_per_point"],
                     "imbalance": prep["partition"]["imbalance"],
                     "overlap_fraction": prep["partition"]["overlap_fraction"],
                     "values_per_step": prep["partition"]["values_exchanged_per_step"]})
    base = rows[0]["loop_s"] * rows[0]["ranks"]
    lines = ["| ranks | particles | steps | loop (s) | speedup | efficiency | seed speedup | comm+wait (ms/step) | "
             "ns/point update (x ranks) | neighbours/point | imbalance | overlap fraction | values/step |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        r["speedup"] = base / r["loop_s"]
        r["efficiency"] = r["speedup"] / r["ranks"]
        seed = SEED_SPEEDUP.get(r["ranks"])
        lines.append(f"| {r['ranks']} | {r['particles']} | {r['steps']} | {r['loop_s']:.2f} | {r['speedup']:.2f} | "
                     f"{100 * r['efficiency']:.1f} % | {seed if seed else '-'} | {r['comm_ms_per_step']:.2f} | "
                     f"{r['ns_per_point_update']:.0f} | {r['neighbours_per_point']:.1f} | {r['imbalance']:.3f} | {r['overlap_fraction']:.4f} | "
                     f"{r['values_per_step']} |")
    table = "\n".join(lines)
    (a.work / "bench.json").write_text(json.dumps(rows, indent=2) + "\n")
    (a.work / "bench.md").write_text(f"Taylor bar, spacing {a.spacing} m, {a.end} s simulated, "
                                     f"{os.cpu_count()} cores\n\n{table}\n")
    print(table)
    print(f"\nwritten: {a.work / 'bench.md'}, {a.work / 'bench.json'}")


if __name__ == "__main__":
    main()
