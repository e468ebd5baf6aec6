"""The studies' smoke versions (two tiny points each) through their Makefile, so the Makefiles and
scripts cannot rot: every case gets a verdict, no output is non-finite, every study writes its CSV,
Markdown table and plots, and a second `make` finds nothing to redo."""
import csv
import subprocess

import rkcase

tools = rkcase.tools_from_argv()
out = tools.work / "studies"
make = ["make", "-C", rkcase.ROOT / "studies", "SMOKE=1", f"BIN={tools.bin}", f"OUT={out}"]
subprocess.run(make + ["clean"], check=True, capture_output=True)
p = subprocess.run(make + ["-j2", "all"], capture_output=True, text=True, env=tools.env)
print(p.stdout[-3000:], p.stderr[-3000:])
rkcase.check(p.returncode == 0, "make -C studies SMOKE=1 -j2 all succeeded")
plots = {"convergence": ["convergence.png"], "tradeoffs": ["pareto.png"], "scaling": ["scaling.png"],
         "stability": [], "features": []}
for study, pngs in plots.items():
    res = out / "results-smoke" / study
    rows = list(csv.DictReader(open(res / "cases.csv")))
    verdicts = {r["case"]: r["verdict"] for r in rows}
    rkcase.check(len(rows) >= 2 and all(v in ("completed", "stopped with a diagnostic", "refused by rkprep", "exceeded the time limit")
                                        for v in verdicts.values()), f"{study}: {verdicts}")
    rkcase.check((res / "table.md").read_text().count("\n|") >= 3, f"{study}: table.md written")
    for png in pngs:
        rkcase.check((res / png).stat().st_size > 10_000, f"{study}: {png} written")
tradeoff = {r["label"]: r for r in csv.DictReader(open(out / "results-smoke" / "tradeoffs" / "cases.csv"))}
ratio = int(tradeoff["cfl 0.25"]["steps"]) / int(tradeoff["default"]["steps"])
rkcase.check(3.2 < ratio < 4.0, f"tradeoffs: CFL 0.25 takes {ratio:.2f}x the steps of the default 0.9 (0.9 / 0.25 = 3.6)")
again = subprocess.run(make + ["-q", "all"], capture_output=True, text=True, env=tools.env)
rkcase.check(again.returncode == 0, "a second make has nothing to redo")
