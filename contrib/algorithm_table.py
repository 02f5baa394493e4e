#!/usr/bin/python3
"""Nested fixed points against the generalized Newton, each with fixed and adaptive stopping: cost and error.

Usage: contrib/algorithm_table.py [--executable build/stabilized_lagrangian] [--jobs N]
           [--scenes NAME ...] [--set 'Section/Entry=value' ...]
           [--workdir DIR] [--output FOLDER | --doc]

For each scene -- the three patins of the seed paper, the Hertz cylinder, the
patin on a deformable block, the two cylinders and the 3D patin, as shipped,
and the 2D patins and Hertz also in one load step -- runs contrib/compare.py with the algorithms
nested (the seed's loops geometry -> friction -> status -> Newton as fixed
points) and newton (the three folded into the generalized Newton), each with
`Nonlinear solver/Stopping = fixed` and `adaptive` (doc/formulation.md,
"Adaptive stopping"). From compare.py's table: the Newton iterations of the
accepted attempts and of those that failed and were cut, the wall time (runs
share the machine --jobs at a time), and the error at the last load step:
against Hertz's closed form, else against compare.py's reference solution (the
scene on a finer mesh, Q2/P1, by the generalized Newton with fixed
tolerances; for the neo-Hookean patin Q1/P1 two refinements finer, where
Q2/P1 does not converge past t = 0.75; for the 3D patin Q1/P1 one refinement
finer, which the direct solver holds).

--set entries apply to every run, the references too (e.g. --set
'Contact/r_t=10'). Writes algorithm_comparison.md and .csv into --output
(default: the work directory; --output may also name the .md file), into doc/
only with --doc; text after the page's end marker, a reading of the results, is
kept when the page is written again. compare.py's own pages and plots stay in the work
directory, one folder per scene and load path."""
import argparse
import csv
import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402
from compare import read_table  # noqa: E402
from robustness_map import write_section  # noqa: E402

# name, title, whether the one-step load path is run, compare.py's reference options
SCENES = [
    ("patin_elastic", "elastic patin", True, []),
    ("patin_neo_hookean", "neo-Hookean patin", True,
     ["--reference-pair", "Q1/P1", "--reference-refinement", "2"]),
    ("patin_elastoplastic", "J2 patin", True, []),
    ("hertz_cylinder", "Hertz cylinder", True, []),
    ("patin_deformable_block", "patin on a deformable block", False, []),
    ("two_cylinders", "two cylinders", False, []),
    ("patin_3d", "3D patin", False, ["--reference-pair", "Q1/P1", "--reference-refinement", "1"]),
]
ERRORS = [("pressure_l2_error", "p L2 error"), ("normal_force_error", "F_n error"),
          ("tangential_force_error", "F_t error"), ("half_width_error", "half-width error")]
ONE_STEP = "Load stepping/Number of load steps=1"
# the part of the page the tool writes; text after it (the reading of the results) is kept
BEGIN = "<!-- written by contrib/algorithm_table.py: begin -->"
END = "<!-- written by contrib/algorithm_table.py: end -->"

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", type=tool_cli.executable,
                    default=os.path.join(tool_cli.ROOT, "build", "stabilized_lagrangian"),
                    help="the program (default: build/stabilized_lagrangian of the repository)")
parser.add_argument("--jobs", type=tool_cli.positive_int, default=2, help="runs at a time (default: %(default)s)")
parser.add_argument("--scenes", nargs="+", choices=[s[0] for s in SCENES], metavar="NAME",
                    help="a subset of the scenes (default: all)")
parser.add_argument("--set", action="append", default=[], metavar="SECTION/ENTRY=VALUE", type=tool_cli.setting)
parser.add_argument("--workdir", default="/tmp/algorithm_table", help="where the runs are (default: %(default)s)")
tool_cli.add_output_arguments(parser, None, ["algorithm_comparison.md", "algorithm_comparison.csv"],
                              file_suffix=".md")
args = tool_cli.parse_with_workdir(parser)
args.workdir = os.path.abspath(args.workdir)


def compare(name, reference_options, settings, folder):
    """compare.py on a scene; its rows {(algorithm, stopping): row}, or the reason it failed."""
    command = [sys.executable, os.path.join(tool_cli.ROOT, "contrib", "compare.py"),
               os.path.join(tool_cli.ROOT, "prm", name + ".prm"), "--executable", args.executable,
               "--algorithms", "nested", "newton", "--stoppings", "fixed", "adaptive",
               "--reference-algorithm", "newton", *reference_options, "--jobs", str(args.jobs),
               "--workdir", folder, "--name", "compare"]
    for setting in settings:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    with open(os.path.join(folder, "compare_log.txt") if os.path.isdir(folder) else os.devnull, "w") as f:
        f.write(result.stdout + result.stderr)
    table = os.path.join(folder, "compare.csv")
    if not os.path.exists(table):
        return f"compare.py exited with {result.returncode}: {(result.stdout + result.stderr).strip()[-300:]}"
    rows = read_table(table)
    with open(os.path.join(folder, "compare.md")) as f:
        reference = next((line for line in f if line.startswith(("Reference:", "**The reference run failed"))), "")
    return {(r["algorithm"], r["stopping"]): r for r in rows}, reference.strip()


def percent(value):
    return "—" if value is None or value == "" else f"{100 * value:.3g} %"


start = time.time()
scenes = [s for s in SCENES if not args.scenes or s[0] in args.scenes]
cases, csv_rows = [], []
for name, title, one_step, reference_options in scenes:
    for path, extra in (("as shipped", []), ("one step", [ONE_STEP]))[:2 if one_step else 1]:
        folder = os.path.join(args.workdir, f"{name}_{path.replace(' ', '_')}")
        print(f"{title}, {path}: contrib/compare.py in {folder}", flush=True)
        outcome = compare(name, reference_options, list(args.set) + extra, folder)
        cases.append((title, path, outcome))
        if isinstance(outcome, str):
            print(f"  failed: {outcome}", flush=True)
            continue
        for (algorithm, stopping), r in outcome[0].items():
            csv_rows.append({"scene": name, "load_path": path, "algorithm": algorithm, "stopping": stopping,
                             **{k: r.get(k, "") for k in ("outcome", "load_steps", "newton_iterations",
                                                          "failed_newton_iterations", "wall_time_s",
                                                          *[c for c, _ in ERRORS], "estimated_relative_error")}})
total = time.time() - start

lines = [BEGIN, "# Nested fixed points against the generalized Newton, fixed and adaptive stopping", "",
         "*Nested*: the seed's loops geometry → friction → status → Newton as fixed points. *Newton*: the "
         "three folded into the generalized Newton (`Method = newton`). *Fixed*: each loop stops at its own "
         "criterion; *adaptive*: also once its error is below `Adaptive stopping fraction` (0.02) of the "
         "estimated discretisation error (doc/formulation.md, \"Adaptive stopping\"). Same scene, r_n, r_t "
         "and tolerances" + (f", with {', '.join(args.set)}" if args.set else "") + ". Newton iterations: "
         "of the accepted attempts, + those of the attempts that failed and were cut. Errors at the last load "
         "step: against Hertz's closed form (contrib/hertz_errors.py), else against a reference solution on a "
         "finer mesh (contrib/compare.py; the reference of each scene below its table). Wall times: runs "
         f"{args.jobs} at a time on the 2-core machine, one MPI rank each, setup and output included.", ""]
header = ["load path", "algorithm", "stopping", "load steps", "Newton it.", "wall (s)"]
by_scene = {}
for title, path, outcome in cases:
    by_scene.setdefault(title, []).append((path, outcome))
for title, paths in by_scene.items():
    lines += [f"## {title}", ""]
    tables = [(path, outcome) for path, outcome in paths if not isinstance(outcome, str)]
    shown = [(c, t) for c, t in ERRORS
             if any(r.get(c) not in (None, "") for _, (rows, _) in tables for r in rows.values())]
    if tables:
        columns = header + [t for _, t in shown] + ["estimate (energy, rel.)"]
        lines += ["| " + " | ".join(columns) + " |", "|" + "---|" * 3 + "---:|" * (len(columns) - 3)]
    for path, (rows, _) in tables:
        for algorithm in ("nested", "newton"):
            for stopping in ("fixed", "adaptive"):
                r = rows.get((algorithm, stopping))
                if r is None:
                    continue
                if r["outcome"] != "converged":
                    lines.append(f"| {path} | {algorithm} | {stopping} | **{r['outcome']}** |"
                                 + " |" * (len(columns) - 4))
                    continue
                failed = int(r["failed_newton_iterations"] or 0)
                cells = [path, algorithm, stopping, f"{r['load_steps']:.0f}",
                         f"{r['newton_iterations']:.0f}" + (f" + {failed}" if failed else ""),
                         f"{r['wall_time_s']:.2f}", *[percent(r.get(c)) for c, _ in shown],
                         percent(r.get("estimated_relative_error"))]
                lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    for path, outcome in paths:
        if isinstance(outcome, str):
            lines.append(f"- {path}: **failed**: {outcome}")
        else:
            lines.append(f"- {path}: {outcome[1] or 'errors against the closed form.'}")
    lines.append("")

words, skip = [], False
for word in sys.argv[1:]:  # as a page shows the command: without the machine's paths
    if skip or word.split("=", 1)[0] in ("--executable", "--workdir"):
        skip = not skip and "=" not in word
        continue
    words.append(word)
command = "contrib/algorithm_table.py " + shlex.join(words)
lines += [f"Generated by `{command.strip()}` ({total / 60:.1f} min). Discussion: doc/robustness.md "
          "(the algorithms); the reading of the stopping below.", END, ""]
md_path = tool_cli.destination(args, "algorithm_comparison.md")
csv_path = md_path[:-3] + ".csv"
write_section(md_path, BEGIN, END, "\n".join(lines))
with open(csv_path, "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(csv_rows[0]) if csv_rows else ["scene"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(csv_rows)
print(f"wrote {tool_cli.shown(md_path)} and {tool_cli.shown(csv_path)} ({total:.0f} s)")
sys.exit(1 if any(isinstance(o, str) for _, _, o in cases) else 0)
