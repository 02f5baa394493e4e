#!/usr/bin/python3
"""Reproducibility of a robustness map: the same r_n x r_t map run with 1 and 2
BLAS threads and with the OpenBLAS kernels of another CPU, compared cell by cell
(doc/newton_criterion.md, "Reproducibility of the J2 map").

    contrib/map_reproducibility.py --executable build/stabilized_lagrangian \\
        --scene prm/patin_elastoplastic.prm --doc

The map is that of contrib/robustness_study.py --part maps (r_n = 1e1..1e13, 9
log points, x r_t = 1e-4..1e6, 11 log points; Maximum step cuts = 0, at most 300
Newton iterations per load step), for each --algorithm (default both), run by
contrib/robustness_map.py's sweep --jobs at a time, in the variants
- threads1: `Linear solver/Threads per rank = 1`;
- threads2: `Linear solver/Threads per rank = 2`;
- prescott: `Threads per rank = 1` and OPENBLAS_CORETYPE=Prescott in the
  environment (OpenBLAS's kernels for an old x86-64 CPU instead of this one's).
A cell differs when its outcome, load steps or Newton iterations differ from
threads1's, or when any loop count of its statistics.csv (geometry, friction,
status and Newton iterations, failed-attempt iterations, assemblies, per step)
or of its iterations.csv (every column but the residual) differs. Writes the
section "Reproducibility of the J2 map" of newton_criterion.md in the --output
folder (default: the work directory; or --output FILE.md), or of
doc/newton_criterion.md with --doc (replaced between its begin/end comments, or
appended), and WORKDIR/<algorithm>_<variant>.csv; exits with 1 if a cell
differs."""
import argparse
import csv
import os
import shlex
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402
from robustness_map import build_scene, log_grid, sweep, write_csv, write_section  # noqa: E402

MAP_RN = (1e1, 1e13, 9)  # the grid of contrib/robustness_study.py --part maps
MAP_RT = (1e-4, 1e6, 11)
NEWTON_BUDGET = "Nonlinear solver/Maximum Newton iterations per load step=300"
VARIANTS = [("threads1", "Linear solver/Threads per rank = 1", {}, 1),
            ("threads2", "Linear solver/Threads per rank = 2", {}, 2),
            ("prescott", "Threads per rank = 1, OPENBLAS_CORETYPE=Prescott", {"OPENBLAS_CORETYPE": "Prescott"}, 1)]
STATISTICS_COUNTS = ["step", "step_cuts", "geometry_iterations", "friction_iterations", "status_iterations",
                     "newton_iterations", "failed_attempt_newton_iterations", "assemblies", "jacobian_assemblies"]
BEGIN, END = "<!-- begin map_reproducibility -->", "<!-- end map_reproducibility -->"


def loop_counts(case_dir):
    """The loop counts a case wrote: statistics.csv's count columns and iterations.csv without residuals."""
    counts = []
    for name, keep in (("statistics.csv", lambda k: k in STATISTICS_COUNTS),
                       ("iterations.csv", lambda k: "residual" not in k)):
        path = os.path.join(case_dir, "output", name)
        if not os.path.exists(path):
            counts.append(None)
            continue
        with open(path) as f:
            counts.append([tuple((k, v) for k, v in row.items() if keep(k)) for row in csv.DictReader(f)])
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--executable", required=True, type=tool_cli.executable)
    parser.add_argument("--scene", required=True, type=tool_cli.existing_file)
    tool_cli.add_output_arguments(parser, None, ["the section of newton_criterion.md"], file_suffix=".md")
    parser.add_argument("--algorithm", action="append", choices=["nested", "newton"],
                        help="repeatable (default: both)")
    parser.add_argument("--jobs", type=tool_cli.positive_int, default=1)
    parser.add_argument("--timeout", type=tool_cli.positive_float, default=600, help="seconds per case")
    parser.add_argument("--workdir", default="/tmp/map_reproducibility", help="default: %(default)s")
    args = parser.parse_args()
    args.output = args.output or args.workdir
    tool_cli.check_output(parser, args)
    output = tool_cli.destination(args, "newton_criterion.md")
    algorithms = args.algorithm or ["nested", "newton"]
    command = " ".join(["contrib/map_reproducibility.py"] + [shlex.quote(a) for a in sys.argv[1:]])
    rn_values, rt_values = log_grid(*MAP_RN), log_grid(*MAP_RT)
    grid = [(i, j) for j in range(len(rt_values)) for i in range(len(rn_values))]  # sweep's order

    lines = []
    total_differ = 0
    for algorithm in algorithms:
        results = {}
        for variant, _, environment, threads in VARIANTS:
            print(f"== {algorithm}, {variant}", flush=True)
            text = build_scene(args.scene, [NEWTON_BUDGET, f"Linear solver/Threads per rank={threads}"],
                               algorithm, max_cuts=0)
            saved = {k: os.environ.get(k) for k in environment}
            os.environ.update(environment)
            start = time.monotonic()
            try:
                rows = sweep(args.executable, text, rn_values, rt_values,
                             os.path.join(args.workdir, f"{algorithm}_{variant}"), args.jobs, args.timeout)
            finally:
                for k, v in saved.items():
                    if v is None:
                        os.environ.pop(k, None)
                    else:
                        os.environ[k] = v
            seconds = time.monotonic() - start
            write_csv(rows, os.path.join(args.workdir, f"{algorithm}_{variant}.csv"))
            counts = [loop_counts(os.path.join(args.workdir, f"{algorithm}_{variant}", f"rn{i:02d}_rt{j:02d}"))
                      for i, j in grid]
            results[variant] = (rows, counts, seconds)
        reference_rows, reference_counts, _ = results["threads1"]
        outcomes = {o: sum(r["outcome"] == o for r in reference_rows) for o in ("converged", "diverged")}
        lines += [f"### {algorithm}", "",
                  f"{len(grid)} cells; with threads1: {outcomes['converged']} converged, {outcomes['diverged']} "
                  f"diverged, {len(grid) - sum(outcomes.values())} error/timeout.", "",
                  "| variant | cells differing from threads1 (outcome, steps, Newton iterations) "
                  "| cells whose loop counts differ (statistics.csv, iterations.csv) | time |",
                  "|---|---|---|---|"]
        for variant, description, _, _ in VARIANTS:
            rows, counts, seconds = results[variant]
            summary_differ = [(r["r_n"], r["r_t"]) for r, ref in zip(rows, reference_rows)
                              if (r["outcome"], r["load_steps"], r["newton_iterations"])
                              != (ref["outcome"], ref["load_steps"], ref["newton_iterations"])]
            counts_differ = [(r["r_n"], r["r_t"]) for r, c, ref in zip(rows, counts, reference_counts) if c != ref]
            if variant != "threads1":
                total_differ += len(set(summary_differ) | set(counts_differ))
            where = "".join(f" ({rn:.3g}, {rt:.3g})" for rn, rt in sorted(set(summary_differ) | set(counts_differ)))
            lines.append(f"| {variant}: {description} | {len(summary_differ)} / {len(rows)} "
                         f"| {len(counts_differ)} / {len(rows)}{' at' + where if where else ''} | {seconds:.0f} s |")
        lines.append("")

    section = [BEGIN, "## Reproducibility of the J2 map", "",
               f"Written by `{command}`.", "",
               f"The r_n × r_t map of `contrib/robustness_study.py --part maps` (r_n = {MAP_RN[0]:g} … "
               f"{MAP_RN[1]:g}, {MAP_RN[2]} points × r_t = {MAP_RT[0]:g} … {MAP_RT[1]:g}, {MAP_RT[2]} points, "
               "Maximum step cuts = 0, at most 300 Newton iterations per load step) of "
               f"`{os.path.basename(args.scene)}`, run three times with `contrib/robustness_map.py`'s sweep "
               f"({args.jobs} case at a time): `Linear solver/Threads per rank = 1` (threads1), `= 2` "
               "(threads2), and `= 1` with OPENBLAS_CORETYPE=Prescott in the environment (prescott: "
               "OpenBLAS's kernels for another CPU). Each is equivalent to",
               "",
               "    contrib/robustness_map.py --executable EXECUTABLE --scene "
               f"{args.scene} --algorithm ALGORITHM --rn 10 1e13 9 --rt 1e-4 1e6 11 \\",
               "        --set 'Nonlinear solver/Maximum Newton iterations per load step=300' \\",
               "        --set 'Linear solver/Threads per rank=1|2' --jobs 1 --output ...",
               "",
               "(OPENBLAS_CORETYPE=Prescott before it for the third). A cell differs when its outcome, load "
               "steps or Newton iterations differ from threads1's; its loop counts differ when any count column "
               "of its statistics.csv (geometry, friction, status, Newton, failed-attempt Newton iterations, "
               "assemblies, per step) or of its iterations.csv (every column but the residual) does. Per-case "
               f"directories: `{args.workdir}/<algorithm>_<variant>/rnII_rtJJ`.", ""] + lines + [
               f"**{total_differ} cell(s) differ** over the {len(algorithms)} × 2 comparisons.", "", END]
    write_section(output, BEGIN, END, "\n".join(section) + "\n")
    print("\n".join(lines))
    print(f"{total_differ} cell(s) differ; wrote the section of {output}")
    return 1 if total_differ else 0


if __name__ == "__main__":
    sys.exit(main())
