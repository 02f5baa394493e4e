#!/usr/bin/python3
"""The iterative linear solver (`Linear solver/Method = iterative`) against the direct one on
every scene of prm/ (issue 21: Newton iteration counts within one per load step, forces to
1e-6 relative, on every scene that runs with it).

Usage: contrib/benchmark_iterative_scenes.py [--executable build/stabilized_lagrangian]
           [--scene NAME ...] [--jobs N] [--timeout SECONDS] [--reuse]
           [--workdir DIR] [--output FOLDER | --doc]

Each prm/*.prm (or each --scene) runs as shipped twice, with `Linear solver/Method = direct`
and with `Linear solver/Method = iterative` appended (relative `Mesh file`s made absolute,
`include`s inlined: robustness_map.read_scene), in WORKDIR/NAME-direct and WORKDIR/NAME-iterative
(WORKDIR: --workdir, default FOLDER/runs), --jobs at a time (default 1: the wall times are
compared), one BLAS thread each; a case running longer than --timeout s is killed.

Per scene: the load steps and Newton iterations of each run (run_summary.csv, failed attempts
included) and per step (statistics.csv), the largest |difference| of the per-step counts, the final
normal and tangential contact force of each and their difference, the largest difference of any
force column (contact, reactions, zones, plates) over all steps, each relative to the run's
scale: the largest force magnitude in the direct run's force columns, all steps. Also the GMRES
iterations, the systems the iterative solver left to the direct one (iterative_fallbacks) and
the wall time of both runs.

Verdict: "agrees" when both runs converge with the same load steps, the per-step Newton counts
differ by at most 1 and every force by at most 1e-6 relative; "differs" otherwise (with the
numbers); "fails" when a run ends in error, divergence or timeout (the program's message is shown:
a scene the iterative solver rejects is listed, not left out).

Writes iterative_scenes.md (a Markdown table, the per-step counts of the scenes that differ,
the messages of those that fail, the command that produced it) and iterative_scenes.csv into the
--output folder (default /tmp/benchmark_iterative_scenes), or into doc/ with --doc.
--reuse: a case whose directory holds a finished run of the same input (case.json) is not run again.
Exit code 1 when a scene differs or fails."""
import argparse
import glob
import json
import os
import shlex
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_map  # noqa: E402
import run_output  # noqa: E402
import tool_cli  # noqa: E402

METHODS = ("direct", "iterative")
NEWTON_TOLERANCE = 1       # per-step Newton iterations
FORCE_TOLERANCE = 1e-6     # relative to the run's largest force magnitude
COLUMNS = ["scene", "dimension", "dofs", "verdict", "direct_outcome", "iterative_outcome",
           "direct_load_steps", "iterative_load_steps", "direct_newton_iterations", "iterative_newton_iterations",
           "direct_failed_attempt_newton_iterations", "iterative_failed_attempt_newton_iterations",
           "direct_newton_per_step", "iterative_newton_per_step", "max_step_difference", "max_loop_difference",
           "direct_normal_force", "iterative_normal_force", "normal_force_relative_difference",
           "direct_tangential_force", "iterative_tangential_force", "tangential_force_relative_difference",
           "force_scale", "max_force_relative_difference", "max_force_column", "max_force_step",
           "gmres_iterations", "gmres_per_newton", "iterative_fallbacks", "schur_node_blocks",
           "direct_wall_time_s", "iterative_wall_time_s", "message"]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", type=tool_cli.executable,
                    default=os.path.join(tool_cli.ROOT, "build", "stabilized_lagrangian"),
                    help="the program (default: build/stabilized_lagrangian of this repository)")
parser.add_argument("--scene", action="append", metavar="NAME",
                    help="a scene of prm/ (name without .prm); repeatable (default: all of prm/*.prm)")
parser.add_argument("--jobs", type=tool_cli.positive_int, default=1,
                    help="cases run at a time (default: %(default)s)")
parser.add_argument("--timeout", type=tool_cli.positive_float, default=900,
                    help="seconds after which a case is killed (default: %(default)s)")
parser.add_argument("--workdir", help="where the runs are (default: FOLDER/runs of --output)")
parser.add_argument("--reuse", action="store_true",
                    help="take a case already run with the same input from the work directory")
tool_cli.add_output_arguments(parser, "/tmp/benchmark_iterative_scenes", ["iterative_scenes.md", "iterative_scenes.csv"])
args = parser.parse_args()
tool_cli.check_output(parser, args)
workdir = os.path.abspath(args.workdir or os.path.join(args.output, "runs"))

prm_dir = os.path.join(tool_cli.ROOT, "prm")
scenes = args.scene or sorted(os.path.splitext(os.path.basename(p))[0] for p in glob.glob(os.path.join(prm_dir, "*.prm")))
for name in scenes:
    if not os.path.isfile(os.path.join(prm_dir, name + ".prm")):
        parser.error(f"argument --scene: prm/{name}.prm does not exist")


def case_text(name, method):
    return (robustness_map.read_scene(os.path.join(prm_dir, name + ".prm"))
            + robustness_map.nested_set("Linear solver/Method", method) + robustness_map.OUTPUT_SECTION)


def reused(text, case_dir):
    """The row of a finished run of `text` in case_dir (--reuse), or None."""
    try:
        with open(os.path.join(case_dir, "input.prm")) as f:
            same = f.read() == text
        with open(os.path.join(case_dir, "case.json")) as f:
            return json.load(f) if same else None
    except (OSError, ValueError):
        return None


start = time.monotonic()
cases = [((name, method), case_text(name, method), os.path.join(workdir, f"{name}-{method}"))
         for name in scenes for method in METHODS]
case_dirs = {key: case_dir for key, _, case_dir in cases}
rows = {key: reused(text, case_dir) for key, text, case_dir in cases} if args.reuse else {}
rows = {key: row for key, row in rows.items() if row is not None}
to_run = [case for case in cases if case[0] not in rows]
if rows:
    print(f"{len(rows)} case(s) taken from {workdir}, {len(to_run)} to run", flush=True)
ran = robustness_map.run_cases(args.executable, to_run, jobs=args.jobs, timeout=args.timeout,
                               label=lambda key, row: f"{key[0]}, {key[1]}: {row['outcome']}, "
                                                      f"{row['wall_time_s']:.1f} s")
for key, row in ran.items():
    with open(os.path.join(case_dirs[key], "case.json"), "w") as f:
        json.dump(row, f)
rows.update(ran)
elapsed = time.monotonic() - start


def output_file(key, name):
    return os.path.join(case_dirs[key], "output", name)


def message(key):
    """What the program said when the run stopped: its error or last lines."""
    try:
        with open(os.path.join(case_dirs[key], "log.txt"), errors="replace") as f:
            lines = [line.rstrip() for line in f]
    except OSError:
        return "no log"
    for i, line in enumerate(lines):
        if line.startswith(("Input error:", "Error:")):
            block = []
            for follow in lines[i:]:
                if not follow.strip() or follow.startswith("----"):
                    if block:
                        break
                    continue
                block.append(follow.strip())
            return " ".join(block)[:600]
    tail = [line.strip() for line in lines if line.strip() and not line.startswith(("|", "+"))][-3:]
    return " / ".join(tail)[:600]


def failure(key):
    """Why a run did not converge, in words."""
    row = rows[key]
    if row["outcome"] == "timeout":
        return f"timeout (killed after {row['wall_time_s']:.0f} s)"
    return f"{row['outcome']} (exit code {row['exit_code']}): {message(key)}"


def run_data(key):
    """(summary, statistics rows) of a converged run, or None."""
    row = rows[key]
    if row["outcome"] != "converged" or not os.path.exists(output_file(key, "statistics.csv")):
        return None
    return (run_output.read_csv(output_file(key, "run_summary.csv"))[0],
            run_output.read_csv(output_file(key, "statistics.csv")))


def force_columns(statistics):
    """The force columns of statistics.csv (named with their 3D unit `_N` by run_output)."""
    return [k for k in statistics[0] if k.endswith("_N") and not k.startswith("final_residual")]


def loop_difference(name):
    """The largest |difference| of the Newton iterations of one Newton loop (a row of
    iterations.csv: a step's geometry, friction and status iteration), or None when the two runs
    did not run the same loops."""
    loops = {}
    for method in METHODS:
        path = output_file((name, method), "iterations.csv")
        if not os.path.exists(path):
            return None
        loops[method] = run_output.read_csv(path)
    names = ("step", "geometry_iteration", "friction_iteration", "status_iteration")
    if [[r[k] for k in names] for r in loops["direct"]] != [[r[k] for k in names] for r in loops["iterative"]]:
        return None
    return max((abs(int(a["newton_iterations"] - b["newton_iterations"]))
                for a, b in zip(loops["direct"], loops["iterative"])), default=0)


def compare(name):
    direct_key, iterative_key = (name, "direct"), (name, "iterative")
    result = dict(scene=name, direct_outcome=rows[direct_key]["outcome"],
                  iterative_outcome=rows[iterative_key]["outcome"],
                  direct_wall_time_s=rows[direct_key]["wall_time_s"],
                  iterative_wall_time_s=rows[iterative_key]["wall_time_s"])
    data = {method: run_data((name, method)) for method in METHODS}
    for method in METHODS:
        if data[method] is None:
            continue
        summary, statistics = data[method]
        result.update({"dimension": int(summary["dimension"]),
                       "dofs": int(summary["displacement_dofs"] + summary["multiplier_dofs"]),
                       f"{method}_load_steps": len(statistics),
                       f"{method}_newton_iterations": int(summary["newton_iterations"]),
                       f"{method}_failed_attempt_newton_iterations": int(summary["failed_attempt_newton_iterations"]),
                       f"{method}_newton_per_step": " ".join(str(int(r["newton_iterations"])) for r in statistics),
                       f"{method}_normal_force": statistics[-1]["normal_force_N"],
                       f"{method}_tangential_force": statistics[-1]["tangential_force_N"]})
        if method == "iterative":
            result.update(gmres_iterations=int(summary.get("krylov_iterations", 0)),
                          iterative_fallbacks=int(summary.get("iterative_fallbacks", 0)),
                          schur_node_blocks=int(summary.get("schur_node_blocks", 0)))
            result["gmres_per_newton"] = round(result["gmres_iterations"] / max(1, summary["newton_iterations"]), 2)
    failed = [method for method in METHODS if data[method] is None]
    if failed:
        result["verdict"] = "fails"
        result["message"] = "; ".join(f"{method}: {failure((name, method))}" for method in failed)
        return result
    (_, direct), (_, iterative) = data["direct"], data["iterative"]
    steps = min(len(direct), len(iterative))
    result["max_step_difference"] = max((abs(int(a["newton_iterations"] - b["newton_iterations"]))
                                         for a, b in zip(direct, iterative)), default=0)
    result["max_loop_difference"] = loop_difference(name)
    columns = [c for c in force_columns(direct) if c in iterative[0]]
    scale = max((abs(r[c]) for r in direct for c in columns), default=0.0)
    result["force_scale"] = scale

    def relative(difference):
        return difference / scale if scale > 0 else difference

    worst = (-1.0, None, None)
    for step in range(steps):
        for column in columns:
            difference = relative(abs(direct[step][column] - iterative[step][column]))
            if difference > worst[0]:
                worst = (difference, column, int(direct[step]["step"]))
    if worst[1] is not None:
        result.update(max_force_relative_difference=worst[0], max_force_column=worst[1], max_force_step=worst[2])
    if len(direct) == len(iterative):
        for kind in ("normal", "tangential"):
            result[f"{kind}_force_relative_difference"] = relative(
                abs(result[f"direct_{kind}_force"] - result[f"iterative_{kind}_force"]))
    reasons = []
    if len(direct) != len(iterative) or any(a["time"] != b["time"] for a, b in zip(direct, iterative)):
        reasons.append(f"load steps {len(direct)} (direct) and {len(iterative)} (iterative)"
                       + (" at other times" if len(direct) == len(iterative) else ""))
    if result["max_step_difference"] > NEWTON_TOLERANCE:
        loop = result["max_loop_difference"]
        reasons.append(f"Newton iterations of a step differ by up to {result['max_step_difference']}"
                       + (" (the runs ran different Newton loops)" if loop is None else
                          f" (of one Newton loop, i.e. one geometry/friction/status iteration, by up to {loop})"))
    if worst[0] > FORCE_TOLERANCE:
        reasons.append(f"{worst[1]} of step {worst[2]} differs by {worst[0]:.1e} relative")
    result["verdict"] = "differs" if reasons else "agrees"
    notes = list(reasons)
    if result.get("iterative_fallbacks"):
        notes.append(f"{result['iterative_fallbacks']} system(s) left to the direct solver")
    if scale == 0:
        notes.append("no force: differences absolute")
    result["message"] = "; ".join(notes)
    return result


results = [compare(name) for name in scenes]


def number(value, form):
    return "" if value is None else format(value, form)


command = shlex.join([tool_cli.shown(sys.argv[0])] + [tool_cli.shown(a) if os.path.isabs(a) else a for a in sys.argv[1:]])
lines = ["# The iterative linear solver on every scene of prm/", "",
         f"Generated by `{command}` "
         f"({len(cases)} runs, {args.jobs} at a time, one MPI rank, one BLAS thread, timeout {args.timeout:g} s; "
         f"{elapsed / 60:.1f} min{' with runs reused' if rows.keys() - ran.keys() else ''}).", "",
         "Each scene as shipped, once with `Linear solver/Method = direct` and once with "
         "`Linear solver/Method = iterative`. Issue 21's target: Newton iterations within "
         f"{NEWTON_TOLERANCE} per load step and forces within {FORCE_TOLERANCE:g} relative. "
         "Newton: the run's Newton iterations in its converged load steps (load steps; + those of attempts "
         "cut by the load step controller); Δ step: the largest |difference| of the Newton iterations of a load "
         "step; Δ loop: of one Newton loop (iterations.csv: one geometry, friction and status iteration of a "
         "step; blank if the runs ran different loops). Forces: the last step's normal and tangential "
         "contact force (N, or N/mm in plane strain) of the direct run, and the |difference| of the iterative "
         "run's, relative to the largest force magnitude of the direct run (contact, reactions, zones, plates, "
         "all steps); worst: the largest relative difference of any force column at any step. GMRES: the "
         "iterative run's GMRES iterations (per Newton iteration); fallbacks: systems it left to the direct "
         "solver.", "",
         "| scene | dim | DoFs | Newton direct (steps) | Newton iterative (steps) | Δ step | Δ loop | normal force | Δ normal | "
         "tangential force | Δ tangential | worst Δ force | GMRES (per Newton) | fallbacks | wall direct (s) | "
         "wall iterative (s) | verdict |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]


def newton(result, method):
    if result.get(f"{method}_newton_iterations") is None:
        return result[f"{method}_outcome"]
    failed = result[f"{method}_failed_attempt_newton_iterations"]
    return (f"{result[f'{method}_newton_iterations']} ({result[f'{method}_load_steps']})"
            + (f" +{failed}" if failed else ""))


for r in results:
    gmres = f"{r['gmres_iterations']} ({r['gmres_per_newton']:.1f})" if r.get("gmres_iterations") is not None else ""
    lines.append(f"| {r['scene']} | {r.get('dimension', '')} | {r.get('dofs', '')} | {newton(r, 'direct')} | "
                 f"{newton(r, 'iterative')} | {number(r.get('max_step_difference'), 'd')} | "
                 f"{number(r.get('max_loop_difference'), 'd')} | "
                 f"{number(r.get('direct_normal_force'), '.6g')} | {number(r.get('normal_force_relative_difference'), '.1e')} | "
                 f"{number(r.get('direct_tangential_force'), '.6g')} | "
                 f"{number(r.get('tangential_force_relative_difference'), '.1e')} | "
                 f"{number(r.get('max_force_relative_difference'), '.1e')} | {gmres} | "
                 f"{number(r.get('iterative_fallbacks'), 'd')} | {r['direct_wall_time_s']:.1f} | "
                 f"{r['iterative_wall_time_s']:.1f} | **{r['verdict']}** |")
counts = {v: [r["scene"] for r in results if r["verdict"] == v] for v in ("agrees", "differs", "fails")}
lines += ["", f"{len(counts['agrees'])} of {len(results)} scenes agree, {len(counts['differs'])} differ, "
          f"{len(counts['fails'])} fail. Wall time of the runs: {sum(r['direct_wall_time_s'] for r in results):.0f} s "
          f"direct, {sum(r['iterative_wall_time_s'] for r in results):.0f} s iterative."]
if counts["differs"]:
    lines += ["", "## Scenes that differ", "",
              "Newton iterations per load step, direct / iterative, and what differs.", ""]
    for r in results:
        if r["verdict"] == "differs":
            lines += [f"- **{r['scene']}**: {r['message']}.", f"  - direct: {r['direct_newton_per_step']}",
                      f"  - iterative: {r['iterative_newton_per_step']}"]
notes = [r for r in results if r["verdict"] != "differs" and r.get("message")]
if notes:
    lines += ["", "## Failures and notes", ""]
    lines += [f"- **{r['scene']}** ({r['verdict']}): {r['message']}" for r in notes]
markdown = tool_cli.destination(args, "iterative_scenes.md")
with open(markdown, "w") as f:
    f.write("\n".join(lines) + "\n")
table = tool_cli.destination(args, "iterative_scenes.csv")
robustness_map.write_csv(results, table, COLUMNS)
print("\n".join(lines[6:]))
print(f"wrote {markdown} and {table} ({elapsed / 60:.1f} min)")
sys.exit(1 if counts["differs"] or counts["fails"] else 0)
