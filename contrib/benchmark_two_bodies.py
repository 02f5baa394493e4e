#!/usr/bin/python3
"""The two-body scenes with the point-wise and the weighted contact conditions (the latter with the
standard and the dual multiplier basis), each with the nested loops and the generalized Newton:
iterations, time, the r_n dependence, the Hertz error, the patch tests.

Usage: contrib/benchmark_two_bodies.py --executable build/stabilized_lagrangian [--workdir DIR]
                                       [--jobs N] [--output FOLDER | --doc]

Runs prm/patin_deformable_block.prm and prm/two_cylinders.prm with `Automatic r_n factor` 1 and
100, prm/ironing.prm (factor 1; as shipped, the soft block's top the slave, and with the die as
the slave), and the contact patch tests prm/contact_patch_test.prm (2D) and
prm/contact_patch_test_3d.prm (3D), each with `Contact/Complementarity` pointwise and weighted (and
weighted with `Finite element pair = Q1/P1 dual`, the scenes' Q1/P1 in the dual basis) and with
the nested loops and the generalized Newton (all three loops folded). For each: how the run
ended, the load steps, Newton iterations (those of cut attempts among them), wall time; for the
factor-100 runs the largest change of a nodal pressure against factor 1 (over every step, against
the peak: the r_n dependence of the discrete solution), and F_t / F_n in the last step; for the two
cylinders the peak pressure against Hertz's p0 at the end of the normal phase (t = 0.5); for the
patch tests the largest |p - 100 MPa| / 100 MPa at a node. A table in two_bodies.md (between marker
comments, the text after them kept) in the --output folder (default: the work directory; doc/
with --doc)."""
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
parser.add_argument("--workdir", default="/tmp/benchmark_two_bodies", help="where the runs are (default: %(default)s)")
parser.add_argument("--jobs", type=tool_cli.positive_int, default=None,
                    help="runs at a time (default: the number of cores)")
tool_cli.add_output_arguments(parser, None, ["two_bodies.md"])
args = parser.parse_args()
args.output = args.output or args.workdir
tool_cli.check_output(parser, args)
workdir = os.path.abspath(args.workdir)

GENERALIZED = "".join(robustness_map.nested_set(f"Nonlinear solver/{loop}/Method", "newton")
                      for loop in ("Geometry loop", "Friction loop", "Status loop"))
SCENES = [("patin on a deformable block", "patin_deformable_block.prm", (1, 100)),
          ("two cylinders", "two_cylinders.prm", (1, 100)),
          ("ironing", "ironing.prm", (1,)),
          ("ironing, die as slave", "ironing.prm", (1,)),
          ("patch test 2D", "contact_patch_test.prm", (1,)),
          ("patch test 3D", "contact_patch_test_3d.prm", (1,))]
CONDITIONS = ("pointwise", "weighted", "weighted dual")
# the two cylinders after the normal phase: Hertz for two equal cylinders (tests/two_cylinders.py)
CYLINDERS = {"E": 200000.0, "nu": 0.3, "R": 50.0, "time": 0.5}
ALGORITHMS = ("nested", "generalized Newton")


# prm/ironing.prm's roles (the soft block's top the slave) and the other way round
SHIPPED_ROLES = "set Contact boundary ids = block_top\n  set Master boundary ids  = die_contact"
DIE_AS_SLAVE = "set Contact boundary ids = die_contact\n  set Master boundary ids  = block_top"


def scene_text(label, file_name, conditions, algorithm, factor):
    text = robustness_map.read_scene(os.path.join(tool_cli.ROOT, "prm", file_name))
    if label.endswith("die as slave"):
        if SHIPPED_ROLES not in text:
            raise SystemExit(f"prm/{file_name} does not make the block's top the slave")
        text = text.replace(SHIPPED_ROLES, DIE_AS_SLAVE)
    # ironing ships with the generalized Newton: the nested variant resets the three loops
    text += "".join(robustness_map.nested_set(f"Nonlinear solver/{loop}/Method",
                                              "newton" if algorithm != "nested" else "fixed point")
                    for loop in ("Geometry loop", "Friction loop", "Status loop"))
    if conditions == "weighted dual":
        text += robustness_map.nested_set("Contact/Finite element pair", "Q1/P1 dual")
    return (text + robustness_map.nested_set("Contact/Complementarity", conditions.split()[0])
            + robustness_map.nested_set("Contact/Automatic r_n factor", factor)
            + robustness_map.OUTPUT_SECTION)


cases = []
for label, file_name, factors in SCENES:
    for conditions in CONDITIONS:
        for algorithm in ALGORITHMS:
            for factor in factors:
                key = (label, conditions, algorithm, factor)
                name = (f"{label.replace(' ', '-').replace(',', '')}-{conditions.replace(' ', '-')}-"
                        f"{algorithm.split()[0]}-{factor}")
                cases.append((key, scene_text(label, file_name, conditions, algorithm, factor),
                              os.path.join(workdir, name)))
case_dirs = {key: case_dir for key, _, case_dir in cases}
rows = robustness_map.run_cases(args.executable, cases, jobs=args.jobs, timeout=1800,
                                label=lambda key, row: f"{key}: {row['outcome']}, {row['wall_time_s']:.0f} s")


def read(path):
    if not os.path.exists(path):
        return []
    return run_output.read_csv(path)


def profiles(key):
    folder = os.path.join(case_dirs[key], "output")
    if not os.path.isdir(folder):
        return []
    return [read(os.path.join(folder, name)) for name in sorted(os.listdir(folder)) if name.startswith("profile-")]


def pressure_change(key, reference):
    """max over steps and nodes of |p - p_reference| against the reference's peak; None if not comparable."""
    a, b = profiles(reference), profiles(key)
    if not a or len(a) != len(b) or any(len(x) != len(y) for x, y in zip(a, b)):
        return None
    peak = max(abs(row["contact_pressure_MPa"]) for step in a for row in step)
    return max(abs(x["contact_pressure_MPa"] - y["contact_pressure_MPa"])
               for step_a, step_b in zip(a, b) for x, y in zip(step_a, step_b)) / peak


def hertz_error(key):
    """|p_max - p0| / p0 of the two cylinders at the end of the normal phase, p0 from the computed
    normal force P: R* = R/2, E* = E / (2 (1 - nu^2)), b = sqrt(4 P R* / (pi E*)), p0 = 2 P / (pi b)."""
    statistics = read(os.path.join(case_dirs[key], "output", "statistics.csv"))
    steps = [k for k, s in enumerate(statistics) if abs(s["time"] - CYLINDERS["time"]) < 1e-9]
    if not steps or len(profiles(key)) <= steps[0]:
        return None
    force = statistics[steps[0]]["normal_force_N"]
    e_star = CYLINDERS["E"] / (2 * (1 - CYLINDERS["nu"] ** 2))
    b = math.sqrt(4 * force * CYLINDERS["R"] / 2 / (math.pi * e_star))
    p0 = 2 * force / (math.pi * b)
    return abs(max(row["contact_pressure_MPa"] for row in profiles(key)[steps[0]]) - p0) / p0


BEGIN = "<!-- written by contrib/benchmark_two_bodies.py: begin -->"
END = "<!-- written by contrib/benchmark_two_bodies.py: end -->"
lines = [BEGIN, "## Two deformable bodies: point-wise and weighted conditions", "",
         "Generated by `contrib/benchmark_two_bodies.py --doc` (one MPI rank). Newton: all iterations, those of "
         "cut attempts in brackets. r_n dependence: the largest change of a nodal pressure with "
         "`Automatic r_n factor` 100 against 1, over every step, against the peak. Patch tests: the largest "
         "|p − 100| / 100 at a node of the last step. Hertz error: the two cylinders' peak pressure against p0 "
         "at the end of the normal phase.", "",
         "| scene | conditions | algorithm | r_n factor | outcome | steps | Newton | time (s) | r_n dependence | "
         "F_t / F_n | Hertz error | patch test error |",
         "|---|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
for label, file_name, factors in SCENES:
    for conditions in CONDITIONS:
        for algorithm in ALGORITHMS:
            for factor in factors:
                key = (label, conditions, algorithm, factor)
                row = rows[key]
                statistics = read(os.path.join(case_dirs[key], "output", "statistics.csv"))
                steps = len(statistics)
                newton = (f"{int(sum(s['newton_iterations'] + s['failed_attempt_newton_iterations'] for s in statistics))}"
                          f" ({int(sum(s['failed_attempt_newton_iterations'] for s in statistics))})"
                          if statistics else "")
                change = pressure_change(key, (label, conditions, algorithm, 1)) if factor != 1 else None
                ratio = ""
                if statistics and statistics[-1]["normal_force_N"] > 0 and "patch" not in label:
                    ratio = f"{statistics[-1]['tangential_force_N'] / statistics[-1]['normal_force_N']:.5f}"
                hertz = hertz_error(key) if label == "two cylinders" else None
                patch = ""
                if "patch" in label and profiles(key):
                    patch = f"{max(abs(r['contact_pressure_MPa'] - 100.) for r in profiles(key)[-1]) / 100.:.1e}"
                lines.append(f"| {label} | {conditions} | {algorithm} | {factor} | {row['outcome']} | {steps} | "
                             f"{newton} | {row['wall_time_s']:.1f} | "
                             f"{'' if change is None else f'{change:.1e}'} | {ratio} | "
                             f"{'' if hertz is None else f'{hertz:.2%}'} | {patch} |")
lines += ["", END]
path = tool_cli.destination(args, "two_bodies.md")
robustness_map.write_section(path, BEGIN, END, "\n".join(lines))
print(f"wrote {path}")
