#!/usr/bin/python3
"""The residual error estimate on Hertz (doc/formulation.md, "Error estimate"):
its effectivity under refinement, estimator-driven against Kelly refinement,
and accuracy targets.

Usage: contrib/benchmark_estimator.py --executable build/stabilized_lagrangian
           [--jobs N] [--workdir DIR] [--output FOLDER | --doc] [--quick] [--reuse]

Scenes: prm/hertz_cylinder.prm (2D) and prm/hertz_sphere.prm (3D), frictionless,
on a coarse start mesh, refined by `Adaptive refinement` cycles.

1. Effectivity. Two indices per cycle:
   - energy: the estimate eta against the energy norm of u_N - u_k, u_N the
     last cycle's displacement (`Errors against the last cycle`); cycles at
     least two refinements from the last only (u_N's own error would bias the
     reference by a quarter at most at order 1);
   - pressure: the pressure estimate (estimated_pressure_error) against the
     relative L2 error of the contact pressure against Hertz's closed form
     with the run's own force (contrib/hertz_errors.py, surface_l2_error:
     the nodal values interpolated linearly, along x in 2D, on the Delaunay
     triangles of the nodes in 3D, within 1.5 a).
   2D: uniform refinement (Q1/P1 six times, Q2/P1 five); 3D: estimator-driven
   refinement (uniform would reach 10^6 DoFs after three).
2. Estimator against Kelly refinement, each with fixed-number marking
   (`Refined fraction` 0.3 of the cells) and bulk marking (the cells
   carrying 0.7 of the squared indicators' sum): the L2 error of the
   pressure against the closed form per cycle, the fewest DoFs at which the
   estimator reaches the last Kelly cycle's error, and the DoFs at equal
   error.
3. Targets (`Adaptive refinement/Target pressure error`, criterion estimator):
   0.1, 0.01 and 0.001 in 2D; 0.1, 0.03 and 0.01 in 3D, with the iterative
   linear solver (`Linear solver/Method = iterative`: the direct solver's
   fill would not let the 3D 0.01 mesh fit in this machine's memory); where
   each run stopped (DoFs, wall time over all cycles) and its true error
   against the target.

2D runs with the indentation 0.05 mm instead of the scene's 1.5 mm: a/R =
0.014, so that the closed form of the half-space is exact to about
(a/R)^2 = 2e-4 on the half disc (with the scene's a/R = 0.1 it is off by
about 1 %, which the errors reach after a few cycles).

Writes benchmark_estimator.md and .csv into --output (default: the work
directory), or into doc/ as error_estimator.md/.csv with --doc."""
import argparse
import concurrent.futures
import csv
import math
import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402
from run_output import profile_steps, read_csv  # noqa: E402
from hertz_errors import hertz_errors  # noqa: E402

ROOT = tool_cli.ROOT
SCENES = {2: "hertz_cylinder.prm", 3: "hertz_sphere.prm"}
START = {2: (2, 2), 3: (1, 2)}  # global, local refinements of the start mesh
# 2D: the indentation (mm) that makes the half-space closed form exact to 2e-4
DELTA_2D = 0.05

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", required=True, type=tool_cli.executable)
parser.add_argument("--jobs", type=tool_cli.positive_int, default=2, help="runs at a time (one MPI rank each)")
parser.add_argument("--workdir", default="/tmp/benchmark_estimator")
parser.add_argument("--quick", action="store_true", help="fewer cycles and targets (a check of the tool)")
parser.add_argument("--reuse", action="store_true",
                    help="keep the runs of an earlier call in the work directory whose scene is unchanged")
tool_cli.add_output_arguments(parser, None, ["error_estimator.md", "error_estimator.csv"])
args = tool_cli.parse_with_workdir(parser)
workdir = os.path.abspath(args.workdir)


def scene(dim, pair, criterion, cycles, extra="", indentation=None, fraction=0.3, bulk=False, solver="direct"):
    with open(os.path.join(ROOT, "prm", SCENES[dim])) as f:
        text = f.read()
    global_refinements, local_refinements = START[dim]
    return text + f"""
subsection Geometry
  subsection half ball
    set Global refinements = {global_refinements}
    set Local refinements = {local_refinements}
  end
end
subsection Contact
  set Finite element pair = {pair}
end
subsection Load stepping
  set Number of load steps = 1
end
{indented(indentation)}subsection Adaptive refinement
  set Cycles = {cycles}
  set Criterion = {criterion}
  set Refined fraction = {fraction}
{"  set Marking = bulk" + chr(10) if bulk else ""}{extra}end
{linear_solver(solver)}subsection Output
  set Output directory = output
  set Write vtu = false
end
"""


def linear_solver(method):
    """`Linear solver/Method` where it is not the default (direct), or nothing."""
    return "" if method == "direct" else f"subsection Linear solver\n  set Method = {method}\nend\n"


def indented(indentation):
    """The top face's indentation (mm) instead of the scene's, or nothing."""
    if indentation is None:
        return ""
    return ("subsection Boundary conditions\n  subsection Dirichlet 1\n    subsection Displacement\n"
            f"      set Function constants = delta={indentation}\n    end\n  end\nend\n")



def pressure_error(dim, directory):
    """The relative L2 error of the last step's pressure against Hertz, with the run's force."""
    statistics = read_csv(os.path.join(directory, "statistics.csv"))[-1]
    last_profile = list(profile_steps(directory).values())[-1]
    force = statistics["normal_force_N"]
    return hertz_errors(dim, force, read_csv(last_profile))["surface_l2_error"]


reused_runs = []


def run(name, dim, text):
    """Run a scene; per cycle: DoFs, the estimates, the true pressure error, wall time."""
    directory = os.path.join(workdir, name)
    output = os.path.join(directory, "output")
    log_path, prm_path = os.path.join(directory, "log.txt"), os.path.join(directory, "input.prm")
    reused = args.reuse and os.path.exists(log_path) and os.path.exists(prm_path) and open(prm_path).read() == text
    if reused:
        reused_runs.append(name)
    start = time.time()
    if not reused:
        os.makedirs(directory, exist_ok=True)
        with open(prm_path, "w") as f:
            f.write(text)
        result = subprocess.run([args.executable, "input.prm"], cwd=directory, capture_output=True, text=True)
        with open(log_path, "w") as f:
            f.write(result.stdout + result.stderr)
    elapsed = time.time() - start
    with open(log_path) as f:
        log = f.read()
    # a run the memory guard stopped before a cycle keeps the cycles it did
    stopped = "would need about" in log
    if not os.path.exists(os.path.join(output, "refinement_cycles.csv")) or (
            "Run summary" not in log.split("Refinement cycle")[-1] and not stopped):
        print(f"  {name}: failed (see {log_path})", flush=True)
        return None
    cycles = read_csv(os.path.join(output, "refinement_cycles.csv"))
    errors = {}
    if os.path.exists(os.path.join(output, "cycle_errors.csv")):
        errors = {int(r["cycle"]): r for r in read_csv(os.path.join(output, "cycle_errors.csv"))}
    rows = []
    for row in cycles:
        k = int(row["cycle"])
        where = os.path.join(output, f"cycle-{k}")
        where = where if os.path.isdir(where) else output
        true_error = pressure_error(dim, where)
        energy = errors.get(k)
        rows.append({"run": name, "dim": dim, "cycle": k, "dofs": int(row["displacement_dofs"]),
                     "estimated_error_sqrtNmm": row["estimated_error_sqrtNmm"],
                     "error_against_last_sqrtNmm": energy["error_against_last_cycle_sqrtNmm"] if energy else "",
                     "energy_effectivity": energy["effectivity_index"] if energy else "",
                     "estimated_pressure_error": row["estimated_pressure_error"],
                     "pressure_error": true_error,
                     "pressure_effectivity": row["estimated_pressure_error"] / true_error,
                     "cycle_wall_time_s": row["wall_time_s"]})
    target = None
    if os.path.exists(os.path.join(output, "target_error.csv")):
        target = read_csv(os.path.join(output, "target_error.csv"))[0]
        target["pressure_error"] = rows[-1]["pressure_error"]
        target["run_wall_time_s"] = elapsed
    print(f"  {name}: {len(rows)} cycles, {rows[-1]['dofs']} DoFs, pressure error {rows[-1]['pressure_error']:.4f}, "
          f"{elapsed:.0f} s", flush=True)
    return {"rows": rows, "target": target, "stopped": stopped}


errors_on = "  set Errors against the last cycle = true\n"
effectivity = {
    "2D Q1/P1 uniform": (2, scene(2, "Q1/P1", "uniform", 3 if args.quick else 6, errors_on, DELTA_2D)),
    "2D Q2/P1 uniform": (2, scene(2, "Q2/P1", "uniform", 3 if args.quick else 5, errors_on, DELTA_2D)),
    "3D Q1/P1 estimator": (3, scene(3, "Q1/P1", "estimator", 3 if args.quick else 5, errors_on)),
    # a smaller fraction: five meshes within the memory of the direct solver
    "3D Q2/P1 estimator": (3, scene(3, "Q2/P1", "estimator", 2 if args.quick else 4, errors_on, fraction=0.2)),
}
# fixed number (30 % of the cells) and bulk marking (the cells carrying 70 %
# of the squared indicators' sum), each with both criteria
MARKINGS = {"": (0.3, False, {2: 4 if args.quick else 12, 3: 3 if args.quick else 4}),
            " bulk": (0.7, True, {2: 6 if args.quick else 20, 3: 4 if args.quick else 8})}
criteria = {f"{dim}D Q1/P1 {criterion}{marking}": (dim, scene(dim, "Q1/P1", criterion, cycles[dim], "",
                                                              DELTA_2D if dim == 2 else None, fraction, bulk))
            for marking, (fraction, bulk, cycles) in MARKINGS.items() for dim in (2, 3)
            for criterion in ("estimator", "Kelly")}
criteria["3D Q1/P1 estimator"] = effectivity["3D Q1/P1 estimator"]
targets_by_dim = {2: (0.1, 0.01) if args.quick else (0.1, 0.01, 0.001),
                  3: (0.3, 0.1) if args.quick else (0.1, 0.03, 0.01)}
targets = {f"{dim}D Q1/P1 target {t:g}": (dim, scene(dim, "Q1/P1", "estimator", 30,
                                                     f"  set Target pressure error = {t}\n",
                                                     DELTA_2D if dim == 2 else None,
                                                     solver="iterative" if dim == 3 else "direct"))
           for dim, ts in targets_by_dim.items() for t in ts}

cases = {**effectivity, **criteria, **targets}
start = time.time()
with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
    futures = {name: pool.submit(run, name.replace(" ", "_").replace("/", ""), dim, text)
               for name, (dim, text) in cases.items()}
    results = {name: future.result() for name, future in futures.items()}
total = time.time() - start

all_rows = [r for result in results.values() if result for r in result["rows"]]
csv_path = tool_cli.destination(args, "error_estimator.csv" if args.doc else "benchmark_estimator.csv")
with open(csv_path, "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(all_rows[0].keys()) if all_rows else ["run"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(all_rows)


def fmt(value, spec):
    return "" if value == "" or value is None else format(value, spec)


lines = ["# The error estimate on Hertz", "",
         "The residual estimate of doc/formulation.md (\"Error estimate\") on the Hertz scenes "
         "(prm/hertz_cylinder.prm, prm/hertz_sphere.prm: E = 200000 MPa, nu = 0.3, R = 100 mm, "
         "frictionless, the indentation in one load step; 2D with 0.05 mm instead of the scene's 1.5 mm, "
         "a/R = 0.014, so that the half-space closed form holds to about 2e-4) from a coarse start mesh.", "",
         "- eta: the estimate in the energy norm; ||u_N - u_k||: the energy norm of the difference "
         "to the last cycle's displacement, carried through the nested refinements (`Errors against "
         "the last cycle`), shown for cycles at least two refinements before the last; energy "
         "effectivity: their ratio;",
         "- pressure estimate: ||p* - lambda_n|| / ||lambda_n|| on the contact surface, p* the recovered "
         "pressure (doc/formulation.md, \"Error estimate\"); pressure error: the relative L2 error of the "
         "contact pressure against Hertz's closed form with the run's own force (contrib/hertz_errors.py, "
         "surface_l2_error); pressure effectivity: their ratio.", ""]


def equal_error_ratios(estimator, kelly):
    """For each estimator cycle whose error Kelly's cycles bracket: its DoFs
    against the DoFs Kelly needs for the same error, from the first pair of
    consecutive Kelly cycles that brackets it, interpolated in log-log."""
    ratios = []
    for row in estimator[1:]:
        e = row["pressure_error"]
        for lo, hi in zip(kelly, kelly[1:]):
            if min(lo["pressure_error"], hi["pressure_error"]) <= e <= max(lo["pressure_error"], hi["pressure_error"]) \
                    and lo["pressure_error"] != hi["pressure_error"]:
                t = math.log(e / lo["pressure_error"]) / math.log(hi["pressure_error"] / lo["pressure_error"])
                ratios.append(row["dofs"] / math.exp(math.log(lo["dofs"]) + t * math.log(hi["dofs"] / lo["dofs"])))
                break
    return ratios


def failed_runs(names):
    return [name for name in names if not results[name]]


lines += ["## 1. Effectivity under refinement", ""]
for name in effectivity:
    result = results[name]
    lines += [f"### {name}", ""]
    if result and result["stopped"]:
        lines += ["The memory guard stopped the run before its next cycle (`Adaptive refinement`: "
                  "the next mesh would not fit); the cycles it did:", ""]
    if not result:
        lines += ["failed (see the work directory)", ""]
        continue
    rows = result["rows"]
    last = rows[-1]["cycle"]
    lines += ["| cycle | DoFs | eta | \\|\\|u_N - u_k\\|\\| | energy effectivity | pressure estimate "
              "| pressure error | pressure effectivity |", "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        # the energy index needs a reference two refinements finer
        shown_energy = r["cycle"] <= last - 2
        lines.append(f"| {r['cycle']} | {r['dofs']} | {r['estimated_error_sqrtNmm']:.4g} | "
                     f"{fmt(r['error_against_last_sqrtNmm'] if shown_energy else '', '.4g')} | "
                     f"{fmt(r['energy_effectivity'] if shown_energy else '', '.2f')} | "
                     f"{r['estimated_pressure_error']:.4f} | {r['pressure_error']:.4f} | "
                     f"{r['pressure_effectivity']:.2f} |")
    energy = [r["energy_effectivity"] for r in rows if r["cycle"] <= last - 2 and r["energy_effectivity"] != ""]
    pressure = [r["pressure_effectivity"] for r in rows]
    summary = (f"Energy effectivity {min(energy):.2f}-{max(energy):.2f} (max/min {max(energy) / min(energy):.2f}); "
               if energy else "")
    summary += (f"pressure effectivity {min(pressure):.2f}-{max(pressure):.2f} "
                f"(max/min {max(pressure) / min(pressure):.2f}) over {len(rows)} meshes.")
    lines += ["", summary, ""]

lines += ["## 2. Estimator-driven against Kelly refinement", "",
          "L2 error of the contact pressure against the closed form, cycle by cycle, both criteria "
          "with the same marking (`Adaptive refinement/Marking`).", ""]
for dim, (marking, (fraction, bulk, _)) in ((d, m) for m in MARKINGS.items() for d in (2, 3)):
    names = [f"{dim}D Q1/P1 {criterion}{marking}" for criterion in ("estimator", "Kelly")]
    title = (f"{dim}D Q1/P1, bulk marking (the cells carrying {fraction:g} of the squared indicators' sum)"
             if bulk else f"{dim}D Q1/P1, fixed number ({fraction:g} of the cells)")
    if failed_runs(names):
        lines += [f"{title}: failed runs: {', '.join(failed_runs(names))}", ""]
        continue
    runs = {n: results[n]["rows"] for n in names}
    estimator, kelly_rows = runs[names[0]], runs[names[1]]
    lines += [f"### {title}", "", "| cycle | estimator: DoFs | error | Kelly: DoFs | error |",
              "|---:|---:|---:|---:|---:|"]
    for k in range(max(len(r) for r in runs.values())):
        cells = []
        for n in names:
            r = runs[n][k] if k < len(runs[n]) else None
            cells += [str(r["dofs"]), f"{r['pressure_error']:.4f}"] if r else ["", ""]
        lines.append(f"| {k} | " + " | ".join(cells) + " |")
    kelly = kelly_rows[-1]
    reached = [r for r in estimator if r["pressure_error"] <= kelly["pressure_error"]]
    # the DoFs each criterion spends per cycle, over the cycles both ran
    both = list(zip(estimator, kelly_rows))
    ratios = [e["dofs"] / k["dofs"] for e, k in both[1:]]
    equal = equal_error_ratios(estimator, kelly_rows)
    lines += ["", f"Kelly's last cycle: error {kelly['pressure_error']:.4f} with {kelly['dofs']} DoFs; "
              + (f"the estimator reaches it with {reached[0]['dofs']} DoFs (cycle {reached[0]['cycle']})."
                 if reached else "the estimator does not reach it within its cycles.")
              + f" Cycle by cycle the estimator's meshes have {min(ratios):.2f}-{max(ratios):.2f} times "
              f"Kelly's DoFs" + (f"; at equal error (Kelly's DoFs for each estimator cycle's error, "
                                 f"interpolated on Kelly's curve in log-log) {min(equal):.2f}-{max(equal):.2f} "
                                 f"times, median {sorted(equal)[len(equal) // 2]:.2f}." if equal else "."), ""]

lines += ["## 3. Accuracy targets", "",
          "`Adaptive refinement/Target pressure error`, `Criterion = estimator`, at most 30 cycles: "
          "where the run stopped, what all its cycles cost, and the true error against the target. "
          "2D with the direct solver, 3D with the iterative one (`Linear solver/Method = iterative`: "
          "GMRES with algebraic multigrid, doc/iterative_solver.md), whose memory grows linearly with "
          "the DoFs.", "",
          "| scene | target | met | cycle | DoFs | pressure estimate | true pressure error | true / target "
          "| Newton iterations | wall time (s) |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
for name in targets:
    result = results[name]
    if result and not result["target"] and result["stopped"]:
        # the memory guard stopped the cycles before the target: the last mesh that fitted
        r = result["rows"][-1]
        lines.append(f"| {name.split(' target')[0]} | {name.split('target ')[1]} | no: the next mesh would not "
                     f"fit in memory | {r['cycle']} | {r['dofs']} | {r['estimated_pressure_error']:.4f} | "
                     f"{r['pressure_error']:.4f} | | | |")
        continue
    if not result or not result["target"]:
        lines.append(f"| {name} | | failed | | | | | | | |")
        continue
    t = result["target"]
    lines.append(f"| {name.split(' target')[0]} | {t['target_pressure_error']:g} | {'yes' if t['met'] else 'no'} | "
                 f"{int(t['cycle'])} | {int(t['displacement_dofs'])} | {t['estimated_pressure_error']:.4f} | "
                 f"{t['pressure_error']:.4f} | {t['pressure_error'] / t['target_pressure_error']:.2f} | "
                 f"{int(t['newton_iterations'])} | {t['wall_time_s']:.1f} |")
command = "contrib/benchmark_estimator.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
reuse_note = (f"; {len(reused_runs)} of them kept from an earlier call, whose cycles took "
              f"{sum(r['cycle_wall_time_s'] for r in all_rows if r['run'] in reused_runs) / 60:.1f} min"
              if reused_runs else "")
lines += ["", f"Generated by `{command}` ({len(cases)} runs, {args.jobs} at a time, one MPI rank each, "
          f"2-core machine: {total / 60:.1f} min{reuse_note}).", ""]
md_path = tool_cli.destination(args, "error_estimator.md" if args.doc else "benchmark_estimator.md")
with open(md_path, "w") as f:
    f.write("\n".join(lines))
print(f"{len(all_rows)} rows in {tool_cli.shown(csv_path)}; table in {tool_cli.shown(md_path)} ({total:.0f} s)")
sys.exit(1 if any(r is None for r in results.values()) else 0)
