#!/usr/bin/python3
"""Sizes that cannot finish: ten adaptive refinement cycles that refine every
cell (Kelly, `Refined fraction = 1`: 4^10 times the cells in 2D) under an
address-space limit of 2 GiB (RLIMIT_AS, as a batch system sets it). Before
each refinement the run estimates the memory of the next mesh from its peak so
far; it must stop before the cycle that cannot fit, with a message naming the
entries to change and exit code 1, the cycles done kept — not die in an
allocation half-way through a cycle."""
import os
import resource
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    text = (f.read() + sltest.nested_set("Geometry/block/Global refinements", 2) +
            sltest.nested_set("Load stepping/Number of load steps", 2) +
            sltest.nested_set("Adaptive refinement/Cycles", 10) +
            sltest.nested_set("Adaptive refinement/Criterion", "Kelly") +
            sltest.nested_set("Adaptive refinement/Refined fraction", 1) + sltest.QUIET_OUTPUT)
os.makedirs(workdir, exist_ok=True)
with open(f"{workdir}/input.prm", "w") as f:
    f.write(text)
limit = 2 * 1024**3
result = subprocess.run([executable, "input.prm"], cwd=workdir, env=sltest.MPI_ENV, capture_output=True,
                        text=True, timeout=1200,
                        preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit)))
log = result.stdout + result.stderr
check(result.returncode == 1 and "Adaptive refinement: the next refinement cycle multiplies the cells by 4" in log
      and "Adaptive refinement/Cycles" in log and "bad_alloc" not in log,
      f"stops before a cycle that cannot fit, exit code {result.returncode}: " +
      next((line[:200] for line in log.splitlines() if line.startswith("Error")), "(no error line)"))
rows = sltest.read_csv(f"{workdir}/output/refinement_cycles.csv")
check(1 <= len(rows) < 11, f"the {len(rows)} cycles done are kept in refinement_cycles.csv")
check.finish()
