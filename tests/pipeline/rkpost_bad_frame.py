"""rkpost with damaged results: one rank's frame whose bytes were changed on disk is
reported, naming the file and the dataset, and skipped; a frame file missing on a rank is reported
and skipped; every other frame is still merged and rkpost exits 0; the last frames missing on every rank
are said against solve.json's count. rksolve writes each frame whole
(temporary name, fsync, rename), so a killed run leaves no half-written frame file behind. Results
of another case, and a frame, solve.json or history.csv of another format, are refused with the file
named and a non-zero exit."""
import json
import shutil
import subprocess
import xml.etree.ElementTree as ET

import h5py

import rkcase

tools = rkcase.tools_from_argv()
case = tools.case("rkpost_bad_frame")
tools.prep(case, 2, sets=["discretization.spacing=1.6e-3"])
tools.solve(case, 2, sets=["time.end=8e-6", "time.output_interval=2e-6"])
rank1 = case / "results" / "rank_0001" / "frame_00002.h5"
rkcase.check(not list((case / "results").rglob("*.tmp")), "no temporary frame file left")
raw = case / "velocity.bin"
subprocess.run(["h5dump", "-d", "/frames/00002/velocity", "-b", "LE", "-o", raw, rank1], check=True,
               capture_output=True)
data, chunk = bytearray(rank1.read_bytes()), raw.read_bytes()
at = data.find(chunk[:64])
rkcase.check(at > 0, f"frame 2's velocity found at byte {at} of rank 1's frame file")
data[at + 100] ^= 0xFF  # one flipped byte: the Fletcher32 checksum no longer matches
rank1.write_bytes(bytes(data))
(case / "results" / "rank_0000" / "frame_00003.h5").unlink()
p = tools.post(case, expect_ok=False)
rkcase.check(p.returncode == 0, f"rkpost exits 0 with one bad frame ({p.returncode})")
rkcase.check("frame 2 skipped" in p.stderr and "rank_0001/frame_00002.h5" in p.stderr and
             "frames/00002/velocity" in p.stderr, f"the damaged frame is reported: {p.stderr.strip()}")
rkcase.check("frame 3 skipped" in p.stderr and "rank_0000/frame_00003.h5: missing" in p.stderr,
             "the missing frame is reported")
merged = [d.get("file") for d in ET.parse(case / "vtk" / "case.pvd").getroot().iter("DataSet")]
rkcase.check(merged == ["frame_00000.vtu", "frame_00001.vtu", "frame_00004.vtu"],
             f"the other 3 of 5 frames are merged: {merged}")
report = (case / "report.md").read_text()  # (the skipped frames were said on stderr alone)
rkcase.check("| **frame skipped by rkpost** | frame 2: " in report and "| **frame skipped by rkpost** | frame 3: " in report
             and "rank_0000/frame_00003.h5: missing" in report, "report.md names the skipped frames")
# frame 0 cut short on rank 0 as well (rkpost read its fields' list from it and stopped, exit 1)
damaged = tools.case("rkpost_bad_frame_0")
shutil.copytree(case, damaged)
first = damaged / "results" / "rank_0000" / "frame_00000.h5"
first.write_bytes(first.read_bytes()[:100])
p = tools.post(damaged, expect_ok=False)
merged = [d.get("file") for d in ET.parse(damaged / "vtk" / "case.pvd").getroot().iter("DataSet")]
rkcase.check(p.returncode == 0 and "frame 0 skipped" in p.stderr and merged == ["frame_00001.vtu", "frame_00004.vtu"],
             f"a damaged frame 0 is skipped as the others: exit {p.returncode}, {merged}, {p.stderr.strip()[:300]}")

# the last frame missing on every rank: nothing in results/ says a frame should follow, but solve.json counts them
cut = tools.case("rkpost_last_frame_missing")
shutil.copytree(case, cut)
for r in (0, 1):
    (cut / "results" / f"rank_{r:04d}" / "frame_00004.h5").unlink()
p = tools.post(cut, expect_ok=False)
rkcase.check(p.returncode == 0 and "solve.json says the run wrote 5 frames, but results/ holds 4" in p.stderr,
             f"frames missing at the end on every rank are said: {p.stderr.strip()[:400]}")

# Another case's results beside new subdomains (copied in by hand: rkprep itself refuses such a
# folder): rkpost merges none of them and says why, with a non-zero exit.
other = tools.case("rkpost_foreign_frames")
tools.prep(other, 2, sets=["discretization.spacing=1.5e-3"])
shutil.copytree(case / "results", other / "results")
(other / "results" / "rank_0000" / "frame_00003.h5").unlink(missing_ok=True)
p = tools.post(other, expect_ok=False)
errors = [ln for ln in p.stderr.splitlines() if "rkpost: error" in ln]
rkcase.check(p.returncode != 0 and len(errors) == 1 and "computed on another scene's subdomains" in errors[0]
             and "re-run rksolve" in errors[0] and not (other / "vtk" / "case.pvd").exists(),
             f"another case's frames are refused: {errors[0] if errors else p.stderr.strip()}")

# Results of another version of rksolve (the contracts of shared/result_frame.hpp and
# shared/run_summary.hpp carry a format): a frame or a solve.json of another format is refused with
# its file named, never read under the wrong layout.
with h5py.File(case / "results" / "rank_0001" / "frame_00001.h5", "r+") as f:
    f.attrs["format"] = 0
p = tools.post(case, expect_ok=False)
errors = [ln for ln in p.stderr.splitlines() if "rkpost: error" in ln]
rkcase.check(p.returncode != 0 and len(errors) == 1 and "rank_0001/frame_00001.h5" in errors[0]
             and "frame format 0, this rkpost reads 1" in errors[0],
             f"a frame of another format is refused: {errors[0] if errors else p.stderr.strip()}")
with h5py.File(case / "results" / "rank_0001" / "frame_00001.h5", "r+") as f:
    f.attrs["format"] = 1
solve = json.loads((case / "solve.json").read_text())
solve["format"] = 7
(case / "solve.json").write_text(json.dumps(solve))
p = tools.post(case, expect_ok=False)
errors = [ln for ln in p.stderr.splitlines() if "rkpost: error" in ln]
rkcase.check(p.returncode != 0 and len(errors) == 1 and "solve.json" in errors[0] and "format 7" in errors[0],
             f"a solve.json of another format is refused: {errors[0] if errors else p.stderr.strip()}")
solve["format"] = 1
(case / "solve.json").write_text(json.dumps(solve))
history = (case / "history.csv").read_text().splitlines()
(case / "history.csv").write_text("\n".join([history[0].replace("kinetic,internal", "internal,kinetic")] + history[1:]))
p = tools.post(case, expect_ok=False)
errors = [ln for ln in p.stderr.splitlines() if "rkpost: error" in ln]
rkcase.check(p.returncode != 0 and len(errors) == 1 and "history.csv" in errors[0] and "column 3 is 'internal'" in errors[0],
             f"a history.csv of other columns is refused: {errors[0] if errors else p.stderr.strip()}")

# A new run of a case removes rkpost's outputs of the old one (vtk/, plots/, report.md): a report kept across
# it gave the old run's Taylor footprint and linked pictures of frames the new run did not write
fresh = tools.case("rkpost_outputs_of_an_old_run")
shutil.copytree(cut, fresh)
tools.post(fresh)
rkcase.check((fresh / "report.md").exists() and (fresh / "vtk" / "case.pvd").exists(), "rkpost wrote its outputs")
tools.solve(fresh, 2, sets=["time.end=4e-6", "time.output_interval=2e-6"])
rkcase.check(not any((fresh / d).exists() for d in ("vtk", "plots", "report.md")),
             "a new run removed the old run's vtk/, plots/ and report.md")

# every frame of a rank gone: nothing can be merged, which is an error, not "0 frames" and exit 0
empty = tools.case("rkpost_no_frame_of_rank_1")
shutil.copytree(cut, empty)
for f in (empty / "results" / "rank_0001").glob("frame_*.h5"):
    f.unlink()
p = tools.post(empty, expect_ok=False)
rkcase.check(p.returncode != 0 and "frames asked for could be merged (each skipped, above)" in p.stderr,
             f"no frame merged is an error: exit {p.returncode}, {p.stderr.strip()[-300:]}")
