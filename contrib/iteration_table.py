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


def read_loops(output_dir, wanted=()):
    """step -> geometry iteration -> friction iteration -> [Newton iterations per status iteration]."""
    with open(os.path.join(output_dir, "iterations.csv")) as f:
        rows = [{k: int(float(v)) if k != "residual_N" else float(v) for k, v in r.items()}
                for r in csv.DictReader(f)]
    steps = OrderedDict()
    for r in rows:
        if not wanted or r["step"] in wanted:
            steps.setdefault(r["step"], OrderedDict()).setdefault(
                r["geometry_iteration"], OrderedDict()).setdefault(r["friction_iteration"], []).append(
                r["newton_iterations"])
    return steps


def markdown_table(output_dir, wanted=()):
    """The table as markdown lines."""
    lines = ["| step | geometry it. | friction it. / geometry it. | status it. / friction it. "
             "| Newton it. / status it. | Newton total |",
             "|---:|---:|---:|---|---|---:|"]
    for step, geometry in read_loops(output_dir, wanted).items():
        step_total = 0
        for g, friction in geometry.items():
            status = [len(newton) for newton in friction.values()]
            newton = [n for per_friction in friction.values() for n in per_friction]
            step_total += sum(newton)
            lines.append(f"| {step} | {g} | {len(friction)} | {' '.join(map(str, status))} "
                         f"| {' '.join(map(str, newton))} | {sum(newton)} |")
        lines.append(f"| {step} | | | | cumulative | **{step_total}** |")
    return lines


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("\n".join(markdown_table(sys.argv[1], {int(s) for s in sys.argv[2:]})))
