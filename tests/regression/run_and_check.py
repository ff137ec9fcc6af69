#!/usr/bin/env python3
"""End to end: the default gaussian_pulse deck runs, prints progress, writes
HDF5 snapshots with XDMF descriptors, the snapshots.xmf time series and a history, and check.py accepts the
result (L2_rel <= 1e-3) and writes its PNG.

usage: run_and_check.py EXE WORKDIR
"""
import os
import shutil
import sys
import xml.etree.ElementTree as ET

from harness import ROOT, Checks, run
import mote

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "gaussian_pulse")
p = run([exe, os.path.join(pdir, "gaussian_pulse.toml"), f"output.dir={work}", "run.progress_interval=0"])
checks = Checks()
checks.check(any(l.startswith("step") and "ETA" in l and "steps/s" in l for l in p.stdout.splitlines()), "progress lines printed")
checks.check("[grid]" in p.stdout and "nx = 128" in p.stdout, "resolved deck printed at start-up")
snaps = mote.list_snapshots(work)
checks.check(len(snaps) == 5, f"5 snapshots for t_end = 0.4, snapshot_dt = 0.1 (got {len(snaps)})")
for s in snaps:
    xmf = s[:-3] + ".xmf"
    ok = os.path.exists(xmf)
    if ok:
        root = ET.parse(xmf).getroot()
        items = [d.text for d in root.iter("DataItem")]
        ok = all(t.split(":")[0] == os.path.basename(s) for t in items) and len(items) == 3
    checks.check(ok, f"{os.path.basename(s)}: XDMF descriptor references its HDF5 datasets")
series = ET.parse(os.path.join(work, "snapshots.xmf")).getroot()
grids = [g for g in series.iter("Grid") if g.get("GridType") == "Uniform"]
refs = [g.find("Geometry/DataItem").text.split(":")[0] for g in grids]
checks.check(refs == [os.path.basename(s) for s in snaps], f"snapshots.xmf: a temporal collection of the {len(snaps)} snapshots")
hist = mote.read_history(os.path.join(work, "history.txt"))
drift = abs(hist["mass"][-1] - hist["mass"][0]) / hist["mass"][0]
checks.check(drift < 1e-13, f"mass conserved: relative drift {drift:.2e} < 1e-13")
png = os.path.join(work, "pulse.png")
c = run([sys.executable, os.path.join(pdir, "check.py"), work, "--max-error", "1e-3", "--plot", png], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0, "check.py: L2_rel within 1e-3")
checks.check(os.path.getsize(png) > 10000, "check.py wrote the PNG")
sys.exit(checks.finish())
