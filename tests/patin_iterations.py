#!/usr/bin/python3
"""The three patin scenes of the seed paper (prm/patin_elastic.prm,
prm/patin_neo_hookean.prm, prm/patin_elastoplastic.prm) run to the end on a
coarse mesh, and the iteration count of every loop (iterations.csv: one row per
Newton loop, with its geometry, friction and status iteration numbers and its
status changes) equals the stored one in tests/reference/ (numdiff, no
tolerance: counts are integers, and every decision the loops take is away from
round-off, tests/reproducibility.py), so any change in convergence behaviour
shows up here. Set SL_UPDATE_REFERENCE=1 to rewrite the references after a change
that is meant to alter them."""
import csv
import os
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
check = sltest.Checker()
numdiff = shutil.which("numdiff")
check(numdiff is not None, "numdiff is installed")

for material in ("elastic", "neo_hookean", "elastoplastic"):
    with open(os.path.join(here, "..", "prm", f"patin_{material}.prm")) as f:
        text = f.read()
    text = text.replace("set Global refinements = 4", "set Global refinements = 3")
    out = f"{workdir}/{material}"
    if not sltest.run_checked(executable, text, out, check, material):
        continue
    counts = os.path.join(out, "iteration_counts.csv")
    with open(os.path.join(out, "output", "iterations.csv")) as f, open(counts, "w", newline="") as g:
        writer = csv.writer(g, lineterminator="\n")
        for row in csv.reader(f):
            writer.writerow(row[:5] + row[7:])  # every column but the two residuals
    reference = os.path.join(here, "reference", f"patin_{material}_iterations.csv")
    if os.environ.get("SL_UPDATE_REFERENCE") == "1":
        shutil.copy(counts, reference)
        print(f"updated {reference}")
    if numdiff is None:
        continue
    result = subprocess.run([numdiff, "--absolute-tolerance=0", "--relative-tolerance=0",
                             "--separators=,\n", reference, counts], capture_output=True, text=True)
    total = sum(int(r["newton_iterations"]) for r in csv.DictReader(open(counts)))
    check(result.returncode == 0,
          f"{material}: iteration counts equal tests/reference/patin_{material}_iterations.csv "
          f"({total} Newton iterations)")
    if result.returncode != 0:
        print(result.stdout[-3000:])
check.finish()
