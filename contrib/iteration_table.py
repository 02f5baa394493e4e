#!/usr/bin/python3
"""Print the seed paper's iteration table from a run's iterations.csv.

Usage: contrib/iteration_table.py OUTPUT_DIR [STEP ...] [--output FOLDER]

For each load step (all, or the STEPs named) and each geometry iteration: the
friction iterations, the status iterations of each friction iteration, the
Newton iterations of each status iteration, and the Newton total; then the
step's total and, in brackets, the cumulative total of the run up to that step
(the seed's table: 1 | 5 | 1 | 5 | 25 and 2 | 1 | 1 | 4 | 4, total 29). The
cumulative total counts every step of the run, printed or not: it is the
`cumulative_newton_iterations` of statistics.csv. Both count the Newton
iterations of the accepted attempts (statistics.csv has those of the attempts
that failed and were cut in `failed_attempt_newton_iterations`).

Exits with 2 and a message if OUTPUT_DIR has no iterations.csv or a STEP is
not a load step of the run."""
import argparse
import os
import sys
from collections import OrderedDict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_output  # noqa: E402
import tool_cli  # noqa: E402


class TableError(Exception):
    """The run's files do not give the table asked for."""


def read_loops(output_dir):
    """step -> geometry iteration -> friction iteration -> [Newton iterations per status iteration],
    every step of the run in its order."""
    path = os.path.join(output_dir, "iterations.csv")
    if not os.path.isfile(path):
        raise TableError(f"{path} not found (is {output_dir} an output directory of the program?)")
    rows = run_output.read_rows(path, str)
    steps = OrderedDict()
    for r in rows:
        steps.setdefault(int(r["step"]), OrderedDict()).setdefault(
            int(r["geometry_iteration"]), OrderedDict()).setdefault(int(r["friction_iteration"]), []).append(
            int(r["newton_iterations"]))
    return steps


def markdown_table(output_dir, wanted=()):
    """The table as markdown lines, of every step or of those in `wanted`."""
    steps = read_loops(output_dir)
    if not steps:
        raise TableError(f"{os.path.join(output_dir, 'iterations.csv')} has no load step (did the run stop "
                         "before the first one converged?)")
    missing = sorted(set(wanted) - set(steps))
    if missing:
        raise TableError(f"step{'s' if len(missing) > 1 else ''} {', '.join(map(str, missing))} "
                         f"not in {os.path.join(output_dir, 'iterations.csv')}: the run has {run_output.describe_steps(steps)}")
    lines = ["| step | geometry it. | friction it. / geometry it. | status it. / friction it. "
             "| Newton it. / status it. | Newton total |",
             "|---:|---:|---:|---|---|---:|"]
    cumulative = 0
    for step, geometry in steps.items():
        step_total = 0
        step_lines = []
        for g, friction in geometry.items():
            status = [len(newton) for newton in friction.values()]
            newton = [n for per_friction in friction.values() for n in per_friction]
            step_total += sum(newton)
            step_lines.append(f"| {step} | {g} | {len(friction)} | {' '.join(map(str, status))} "
                              f"| {' '.join(map(str, newton))} | {sum(newton)} |")
        # summed over every step, so that a step printed alone still shows the run's count
        cumulative += step_total
        if not wanted or step in wanted:
            lines += step_lines
            lines.append(f"| {step} | | | | step total (cumulative) | **{step_total}** ({cumulative}) |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output_dir", metavar="OUTPUT_DIR", type=tool_cli.existing_directory,
                        help="the run's output directory (holding iterations.csv)")
    parser.add_argument("steps", metavar="STEP", nargs="*", type=int, help="load steps to print (default: all)")
    parser.add_argument("--output", metavar="FOLDER",
                        help="also write the table to FOLDER/iteration_table.md (created if needed)")
    args = parser.parse_args()
    if args.output and os.path.exists(args.output) and not os.path.isdir(args.output):
        parser.error(f"argument --output: '{args.output}' exists and is not a directory")
    try:
        lines = markdown_table(args.output_dir, set(args.steps))
    except TableError as error:
        parser.error(str(error))
    except (KeyError, ValueError) as error:  # a file of another layout
        parser.error(f"cannot read {os.path.join(args.output_dir, 'iterations.csv')}: {error!r}")
    print("\n".join(lines))
    if args.output:
        os.makedirs(args.output, exist_ok=True)
        path = os.path.join(args.output, "iteration_table.md")
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
