#!/usr/bin/python3
"""Every scene in prm/ runs as shipped, to its end time, and its output has one
statistics row per converged load step with no NaN."""
import glob
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
for prm in sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "prm", "*.prm"))):
    name = os.path.splitext(os.path.basename(prm))[0]
    text = sltest.read_prm(prm)
    out = f"{workdir}/{name}"
    if not sltest.run_checked(executable, text, out, check, name):
        continue
    rows = sltest.read_csv(out + "/output/statistics.csv")
    check(rows and abs(rows[-1]["time"] - 1.0) < 1e-12, f"{name}: {len(rows)} load steps up to t = 1")
    check(all(math.isfinite(v) for r in rows for v in r.values()), f"{name}: no NaN in statistics.csv")
check.finish()
