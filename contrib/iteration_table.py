#!/usr/bin/python3
"""Print the seed paper's iteration table from a run's iterations.csv.

Usage: contrib/iteration_table.py OUTPUT_DIR [STEP ...]

For each load step and each geometry iteration: the friction iterations, the
status iterations of each friction iteration, the Newton iterations of each
status iteration, and the Newton total; then the step's cumulative total
(the seed's table: 1 | 5 | 1 | 5 | 25 and 2 | 1 | 1 | 4 | 4, total 29)."""
import csv
import os
import sys
from collections import OrderedDict

if len(sys.argv) < 2:
    sys.exit(__doc__)
with open(os.path.join(sys.argv[1], "iterations.csv")) as f:
    rows = [{k: int(float(v)) if k != "residual_N" else float(v) for k, v in r.items()}
            for r in csv.DictReader(f)]
wanted = {int(s) for s in sys.argv[2:]}

steps = OrderedDict()
for r in rows:
    if not wanted or r["step"] in wanted:
        steps.setdefault(r["step"], OrderedDict()).setdefault(
            r["geometry_iteration"], OrderedDict()).setdefault(r["friction_iteration"], []).append(
            r["newton_iterations"])

print("| step | geometry it. | friction it. / geometry it. | status it. / friction it. "
      "| Newton it. / status it. | Newton total |")
print("|---:|---:|---:|---|---|---:|")
for step, geometry in steps.items():
    step_total = 0
    for g, friction in geometry.items():
        status = [len(newton) for newton in friction.values()]
        newton = [n for per_friction in friction.values() for n in per_friction]
        step_total += sum(newton)
        print(f"| {step} | {g} | {len(friction)} | {' '.join(map(str, status))} "
              f"| {' '.join(map(str, newton))} | {sum(newton)} |")
    print(f"| {step} | | | | cumulative | **{step_total}** |")
