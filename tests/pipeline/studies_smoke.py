"""The studies' smoke versions (two tiny points each) through their Makefile, so the Makefiles and
scripts cannot rot: every case of studies/studies.py's smoke lists is there with the verdict it is
expected to get, every study writes its CSV, Markdown table and plots, and a second `make` finds
nothing to redo."""
import csv
import subprocess
import sys

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
# The smoke lists of studies/studies.py (SMOKE=1) and the verdict each case must get. None is built
# to be refused or to stop: the refused settings (the stability study's dilation 1.2 and 1.0, below
# the linear basis' minimum 1.5) are in the full lists only, and the stability study's CFL 2.0
# completes (the step estimate is conservative: docs/studies.md, 0.45 % energy error at 40 us).
# "completed" also says the output is finite (a NaN turns it into "NON-FINITE OUTPUT"); a case that
# stops, is refused or runs past CASE_TIMEOUT fails here.
EXPECTED = {
    "convergence": {"taylor_h1.6": "completed", "taylor_h1.2": "completed", "taylor_nodal_h1.6": "completed",
                    "taylor_nodal_h1.2": "completed", "taylor_frequency_h1.6": "completed", "taylor_frequency_h1.2": "completed",
                    "taylor_gauss1_h1.6": "completed", "taylor_gauss1_h1.2": "completed",
                    "upsetting_h3.0": "completed", "upsetting_h2.5": "completed"},
    "tradeoffs": {"taylor_default": "completed", "taylor_cfl_0.25": "completed", "upsetting_penalty0.25": "completed"},
    "stability": {"taylor_jitter_0.4": "completed", "taylor_cfl_2.0": "completed"},
    "features": {"taylor_j2": "completed", "taylor_elastic": "completed"},
    "scaling": {"taylor_n1": "completed", "taylor_n2": "completed"},
}
for study, pngs in plots.items():
    res = out / "results-smoke" / study
    rows = list(csv.DictReader(open(res / "cases.csv")))
    verdicts = {r["case"]: r["verdict"] for r in rows}
    rkcase.check(len(rows) == len(verdicts) and verdicts == EXPECTED[study],
                 f"{study}: every case with its expected verdict: {verdicts}"
                 + ("" if verdicts == EXPECTED[study] else f" (expected {EXPECTED[study]})"))
    rkcase.check((res / "table.md").read_text().count("\n|") >= 3, f"{study}: table.md written")
    for png in pngs:
        rkcase.check((res / png).stat().st_size > 10_000, f"{study}: {png} written")
tradeoff = {r["label"]: r for r in csv.DictReader(open(out / "results-smoke" / "tradeoffs" / "cases.csv"))}
ratio = int(tradeoff["cfl 0.25"]["steps"]) / int(tradeoff["default"]["steps"])
rkcase.check(3.2 < ratio < 4.0, f"tradeoffs: CFL 0.25 takes {ratio:.2f}x the steps of the default 0.9 (0.9 / 0.25 = 3.6)")
again = subprocess.run(make + ["-q", "all"], capture_output=True, text=True, env=tools.env)
rkcase.check(again.returncode == 0, "a second make has nothing to redo")

# the observed order from three resolutions whose ratios differ (the convergence series' 0.3, 0.25,
# 0.185 mm): f = 7.22 + 0.5 h^2 gives 2, and differences of opposite signs no order
sys.path.insert(0, str(rkcase.ROOT / "studies"))
from studies import observed_order  # noqa: E402
levels = [{"h": h, "f": 7.22 + 0.5 * h ** 2} for h in (0.3, 0.25, 0.185)]
wobble = [{"h": 0.3, "f": 7.232}, {"h": 0.25, "f": 7.238}, {"h": 0.185, "f": 7.228}]
rkcase.check(observed_order(levels, "f") == ["0.25: 2.00"] and observed_order(wobble, "f") == ["0.25: oscillates"],
             f"the observed order: {observed_order(levels, 'f')} (2 expected), {observed_order(wobble, 'f')}")
