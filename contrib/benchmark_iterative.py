#!/usr/bin/python3
"""The iterative linear solver (`Linear solver/Method = iterative`) against MUMPS: cost per Newton
iteration, GMRES iterations and memory under refinement, on the 3D Hertz sphere, and the forcing
terms compared on the 2D patin.

Usage: contrib/benchmark_iterative.py --executable build/stabilized_lagrangian [--workdir DIR]
                                      [--quick | --finest 4] [--output FOLDER | --doc]

Runs prm/hertz_sphere.prm (linear elastic half ball on a rigid plane, Q1/P1, frictionless, one
load step) with `Global refinements` 1, 2, 3 (and `Local refinements` 3; --finest 4 adds the
1.3M-DoF mesh, iterative only, 8 GB) with the direct solver and the iterative one in three variants
(the default; `Schur augmentation = 0`; `AMG near-null space = rigid body modes`), one run at a
time (the timings are the point), and prm/patin_elastic.prm with the direct solver and the
iterative one with each `Forcing term`. For each run: DoFs, Newton iterations, GMRES iterations
(per Newton iteration), the `linear solve` time per Newton iteration, the peak memory, and the
normal force (the solvers must agree). The log-log slopes of the solve time per Newton iteration
and of the GMRES iterations per solve against the DoFs are written below the table.
--quick: the two coarser meshes only. A table in iterative_solver.md (between marker comments,
the text after them kept) in the --output folder (default: the work directory; doc/ with --doc)."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_map  # noqa: E402
import run_output  # noqa: E402
import tool_cli  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", required=True, type=tool_cli.executable)
parser.add_argument("--workdir", default="/tmp/benchmark_iterative", help="where the runs are (default: %(default)s)")
parser.add_argument("--quick", action="store_true", help="the two coarser Hertz meshes only")
parser.add_argument("--finest", type=int, choices=(3, 4), default=3,
                    help="the finest Hertz refinement (4: 1.3M DoFs, the default iterative solver only)")
tool_cli.add_output_arguments(parser, None, ["iterative_solver.md"])
args = tool_cli.parse_with_workdir(parser)
workdir = os.path.abspath(args.workdir)

HERTZ = robustness_map.read_scene(os.path.join(tool_cli.ROOT, "prm", "hertz_sphere.prm"))
PATIN = robustness_map.read_scene(os.path.join(tool_cli.ROOT, "prm", "patin_elastic.prm"))
GLOBAL = "set Global refinements      = 2"
if GLOBAL not in HERTZ:
    raise SystemExit(f"prm/hertz_sphere.prm has no '{GLOBAL}'")
refinements = (1, 2) if args.quick else tuple(range(1, args.finest + 1))
ITERATIVE = robustness_map.nested_set("Linear solver/Method", "iterative")
# the solvers compared on the Hertz sphere: label, the entries they set
METHODS = {"direct": "",
           "iterative": ITERATIVE,
           "iterative, no augmentation": ITERATIVE + robustness_map.nested_set("Linear solver/Schur augmentation", "0"),
           "iterative, rigid body modes": ITERATIVE + robustness_map.nested_set(
               "Linear solver/AMG near-null space", "rigid body modes")}

cases = []
for refinement in refinements:
    for method, entries in METHODS.items():
        if refinement > 3 and method != "iterative":
            continue
        text = HERTZ.replace(GLOBAL, f"set Global refinements      = {refinement}")
        text += entries + robustness_map.OUTPUT_SECTION
        cases.append((("Hertz sphere 3D", refinement, method), text,
                      os.path.join(workdir, f"hertz-{refinement}-{method.replace(' ', '-').replace(',', '')}")))
for method, forcing in (("direct", ""), ("iterative", "Newton tolerance"), ("iterative", "Eisenstat-Walker")):
    text = PATIN + (ITERATIVE + robustness_map.nested_set("Linear solver/Forcing term", forcing)
                    if method == "iterative" else "") + robustness_map.OUTPUT_SECTION
    label = method if method == "direct" else f"iterative, {forcing}"
    cases.append((("patin 2D", 0, label), text, os.path.join(workdir, f"patin-{label.replace(' ', '-')}")))
case_dirs = {key: case_dir for key, _, case_dir in cases}
rows = robustness_map.run_cases(args.executable, cases, jobs=1, timeout=3600,
                                label=lambda key, row: f"{key}: {row['outcome']}, {row['wall_time_s']:.0f} s")


def summary(key):
    path = os.path.join(case_dirs[key], "output", "run_summary.csv")
    if not os.path.exists(path):
        return None
    return run_output.read_csv(path)[0]


def last_force(key):
    path = os.path.join(case_dirs[key], "output", "statistics.csv")
    return run_output.read_csv(path)[-1]["normal_force_N"]


def slope(points):
    """Least-squares slope of log y against log x."""
    xs, ys = [math.log(x) for x, _ in points], [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


BEGIN = "<!-- written by contrib/benchmark_iterative.py: begin -->"
END = "<!-- written by contrib/benchmark_iterative.py: end -->"
lines = [BEGIN, "## The iterative linear solver against MUMPS", "",
         f"Generated by `contrib/benchmark_iterative.py --doc{' --quick' if args.quick else ''}` (one MPI rank, "
         "one run at a time, one BLAS thread). Solve per Newton iteration: the `linear solve` section of the "
         "run's timer (for the iterative solver: the block extraction, the AMG and Schur set-up and GMRES) over "
         "the Newton iterations.", "",
         "| scene | refinement | solver | DoFs | Newton | GMRES | GMRES per solve | solve per Newton it. (s) | "
         "peak memory (MiB) | normal force (N) |",
         "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
per_iteration = {method: [] for method in METHODS}
krylov = {method: [] for method in METHODS if method != "direct"}
for key, _, _ in cases:
    scene, refinement, method = key
    s = summary(key)
    if s is None or rows[key]["outcome"] != "converged":
        lines.append(f"| {scene} | {refinement} | {method} | | | | | | | {rows[key]['outcome']} |")
        continue
    dofs = int(s["displacement_dofs"] + s["multiplier_dofs"])
    newton = int(s["newton_iterations"])
    gmres = int(s.get("krylov_iterations", 0))
    solve = s["linear_solve_s"] / newton
    if scene.startswith("Hertz"):
        per_iteration[method].append((dofs, solve))
        if method != "direct":
            krylov[method].append((dofs, gmres / newton))
    lines.append(f"| {scene} | {refinement} | {method} | {dofs} | {newton} | {gmres if gmres else ''} | "
                 f"{f'{gmres / newton:.1f}' if gmres else ''} | {solve:.3f} | {s['peak_memory_MiB']:.0f} | "
                 f"{last_force(key):.6g} |")
lines.append("")
for method, points in per_iteration.items():
    if len(points) >= 2:
        lines.append(f"- Hertz sphere, {method}: solve time per Newton iteration ~ DoFs^{slope(points):.2f}"
                     + (f"; over the last three meshes ~ DoFs^{slope(points[-3:]):.2f}." if len(points) > 3 else "."))
    if len(krylov.get(method, [])) >= 2:
        counts = krylov[method]
        lines.append(f"- Hertz sphere, {method}: GMRES iterations per solve ~ DoFs^{slope(counts):.2f} "
                     f"({' to '.join(f'{c:.1f}' for _, c in counts)}; largest over smallest of the last three "
                     f"meshes {max(c for _, c in counts[-3:]) / min(c for _, c in counts[-3:]):.2f}).")
lines += ["", END]
path = tool_cli.destination(args, "iterative_solver.md")
robustness_map.write_section(path, BEGIN, END, "\n".join(lines))
print(f"wrote {path}")
