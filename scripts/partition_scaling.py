#!/usr/bin/python3
"""Partition report against the rank count: rkprep only (no solve), one part, several --ranks.

  scripts/partition_scaling.py SCENE --spacing H --ranks 2 4 8 16 32 64 --work DIR [--rkprep BIN]

For each N: rkprep SCENE --ranks N --out DIR/N --set discretization.spacing=H, then one row per N from
DIR/N/prep.json (mean and largest owned, overlap and exchanged values per rank, neighbours,
overlap fraction, prep wall and peak memory). Rows go to stdout and DIR/partition_scaling.csv;
at the end the fit overlap per rank = c (owned per rank)^(2/3) by least squares in c.
A value exchanged per step is one 64-bit fixed-point force component sent (and one received).
"""
import argparse, csv, json, os, subprocess

ap = argparse.ArgumentParser()
ap.add_argument("scene")
ap.add_argument("--spacing", required=True)
ap.add_argument("--ranks", type=int, nargs="+", required=True)
ap.add_argument("--work", required=True)
ap.add_argument("--rkprep", default="build/bin/rkprep")
a = ap.parse_args()
os.makedirs(a.work, exist_ok=True)
rows = []
for n in a.ranks:
    out = os.path.join(a.work, str(n))
    subprocess.run(["nice", "-n", "10", a.rkprep, a.scene, "--ranks", str(n), "--out", out, "--force",
                    "--set", f"discretization.spacing={a.spacing}"], check=True, stdout=subprocess.DEVNULL)
    p = json.load(open(os.path.join(out, "prep.json")))
    rk = p["partition"]["ranks"]
    own = [r["owned_particles"] for r in rk]
    ovl = [r["overlap_particles"] for r in rk]
    val = [r["values_exchanged_per_step"] for r in rk]
    nb = [len(r["neighbour_ranks"]) for r in rk]
    rows.append(dict(ranks=n, particles=p["particles"], owned_mean=sum(own) / n, owned_max=max(own),
                     overlap_mean=sum(ovl) / n, overlap_max=max(ovl), values_mean=sum(val) / n,
                     values_max=max(val), neighbours_mean=sum(nb) / n, neighbours_max=max(nb),
                     overlap_fraction=p["partition"]["overlap_fraction"], imbalance=p["partition"]["imbalance"],
                     prep_s=p["wall_s"], prep_peak_mb=p["peak_memory_mb"]))
    r = rows[-1]
    print(" ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in r.items()), flush=True)
with open(os.path.join(a.work, "partition_scaling.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
num = sum(r["overlap_mean"] * r["owned_mean"] ** (2 / 3) for r in rows)
den = sum(r["owned_mean"] ** (4 / 3) for r in rows)
c = num / den
print(f"fit: overlap per rank = {c:.3f} (owned per rank)^(2/3)")
for r in rows:
    print(f"  ranks {r['ranks']}: measured {r['overlap_mean']:.0f}, fit {c * r['owned_mean'] ** (2 / 3):.0f}, "
          f"values per overlap particle {r['values_mean'] / max(r['overlap_mean'], 1):.2f}")
