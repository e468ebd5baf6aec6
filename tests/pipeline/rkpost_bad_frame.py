"""rkpost with a damaged results file (issue 8): one rank's frame whose bytes were changed on disk
(as a write cut short would leave them) is reported, naming the file and the dataset, and skipped;
every other frame is still merged and rkpost exits 0."""
import subprocess
import xml.etree.ElementTree as ET

import rkcase

tools = rkcase.tools_from_argv()
case = tools.case("rkpost_bad_frame")
tools.prep(case, 2, sets=["discretization.spacing=1.6e-3"])
tools.solve(case, 2, sets=["time.end=8e-6", "time.output_interval=2e-6"])
rank1 = case / "results" / "rank_0001.h5"
raw = case / "velocity.bin"
subprocess.run(["h5dump", "-d", "/frames/00002/velocity", "-b", "LE", "-o", raw, rank1], check=True,
               capture_output=True)
data, chunk = bytearray(rank1.read_bytes()), raw.read_bytes()
at = data.find(chunk[:64])
rkcase.check(at > 0, f"frame 2's velocity found at byte {at} of {rank1.name}")
data[at + 100] ^= 0xFF  # one flipped byte: the Fletcher32 checksum no longer matches
rank1.write_bytes(bytes(data))
p = tools.post(case, expect_ok=False)
rkcase.check(p.returncode == 0, f"rkpost exits 0 with one bad frame ({p.returncode})")
rkcase.check("frame 2 skipped" in p.stderr and "rank_0001.h5" in p.stderr and "frames/00002/velocity" in p.stderr,
             f"the bad frame is reported: {p.stderr.strip()}")
merged = [d.get("file") for d in ET.parse(case / "vtk" / "case.pvd").getroot().iter("DataSet")]
rkcase.check(len(merged) == 4, f"the other 4 of 5 frames are merged: {merged}")
