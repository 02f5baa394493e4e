#!/usr/bin/python3
"""Adaptive stopping of the Newton iteration (`Nonlinear solver/Stopping =
adaptive`, doc/formulation.md, "Adaptive stopping") against the fixed
tolerance, on the three patins of the paper and the Hertz cylinder.

Usage: contrib/benchmark_adaptive_stopping.py --executable build/stabilized_lagrangian
           [--jobs N] [--workdir DIR] [--fraction F] [--output FOLDER | --doc]

Each scene runs as shipped, once with `Stopping = fixed` and once with
`adaptive` (`Adaptive stopping fraction` F, default 0.1): Newton iterations
and wall time of the whole load path, the estimated relative discretisation
error of the last step, and what the early stops change: the largest
difference of the last step's contact pressure between the two runs, against
the largest pressure, and of the normal and tangential forces; for Hertz
also the relative L2 error of the pressure against the closed form
(contrib/hertz_errors.py).

Writes adaptive_stopping.md and .csv into --output (default: the work
directory), or into doc/ with --doc."""
import argparse
import concurrent.futures
import csv
import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402
from run_output import profile_steps, read_csv  # noqa: E402
from hertz_errors import hertz_errors  # noqa: E402

SCENES = ["patin_elastic", "patin_neo_hookean", "patin_elastoplastic", "hertz_cylinder"]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", required=True, type=tool_cli.executable)
parser.add_argument("--jobs", type=tool_cli.positive_int, default=2, help="runs at a time (one MPI rank each)")
parser.add_argument("--workdir", default="/tmp/benchmark_adaptive_stopping")
parser.add_argument("--fraction", type=tool_cli.positive_float, default=0.1,
                    help="Adaptive stopping fraction (default 0.1)")
tool_cli.add_output_arguments(parser, None, ["adaptive_stopping.md", "adaptive_stopping.csv"])
args = tool_cli.parse_with_workdir(parser)



def run(scene, mode):
    """Run a scene with a stopping mode; its totals and the last step's profile."""
    directory = os.path.join(os.path.abspath(args.workdir), f"{scene}_{mode}")
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(tool_cli.ROOT, "prm", scene + ".prm")) as f:
        text = f.read()
    text += f"""
subsection Nonlinear solver
  set Stopping = {mode}
  set Adaptive stopping fraction = {args.fraction}
end
subsection Output
  set Output directory = output
  set Write vtu = false
end
"""
    with open(os.path.join(directory, "input.prm"), "w") as f:
        f.write(text)
    start = time.time()
    result = subprocess.run([args.executable, "input.prm"], cwd=directory, capture_output=True, text=True)
    elapsed = time.time() - start
    with open(os.path.join(directory, "log.txt"), "w") as f:
        f.write(result.stdout + result.stderr)
    output = os.path.join(directory, "output")
    if result.returncode != 0 or not os.path.exists(os.path.join(output, "run_summary.csv")):
        print(f"  {scene} {mode}: failed (see {directory}/log.txt)", flush=True)
        return None
    summary = read_csv(os.path.join(output, "run_summary.csv"))[0]
    last = read_csv(os.path.join(output, "statistics.csv"))[-1]
    last_profile = list(profile_steps(output).values())[-1]
    print(f"  {scene} {mode}: {summary['newton_iterations']:.0f} Newton iterations, {elapsed:.1f} s", flush=True)
    return {"newton": int(summary["newton_iterations"]), "steps": int(summary["load_steps"]),
            "wall": summary["wall_time_s"], "estimate": summary["estimated_relative_error"],
            "fn": last["normal_force_N"], "ft": last.get("tangential_force_N", 0.),
            "profile": read_csv(last_profile)}


start = time.time()
with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
    futures = {(scene, mode): pool.submit(run, scene, mode) for scene in SCENES for mode in ("fixed", "adaptive")}
    results = {key: future.result() for key, future in futures.items()}
total = time.time() - start

rows = []
for scene in SCENES:
    fixed, adaptive = results[(scene, "fixed")], results[(scene, "adaptive")]
    if not fixed or not adaptive:
        rows.append({"scene": scene, "failed": True})
        continue
    largest = max(abs(r["contact_pressure_MPa"]) for r in fixed["profile"])
    difference = max(abs(a["contact_pressure_MPa"] - b["contact_pressure_MPa"])
                     for a, b in zip(fixed["profile"], adaptive["profile"]))
    row = {"scene": scene, "failed": False,
           "newton_fixed": fixed["newton"], "newton_adaptive": adaptive["newton"],
           "steps_fixed": fixed["steps"], "steps_adaptive": adaptive["steps"],
           "wall_fixed_s": fixed["wall"], "wall_adaptive_s": adaptive["wall"],
           "estimated_relative_error": fixed["estimate"],
           "pressure_difference": difference / largest,
           "normal_force_difference": abs(adaptive["fn"] - fixed["fn"]) / abs(fixed["fn"]),
           "tangential_force_difference": (abs(adaptive["ft"] - fixed["ft"]) / abs(fixed["ft"])
                                           if fixed["ft"] else 0.)}
    if scene.startswith("hertz"):
        row["hertz_error_fixed"] = hertz_errors(2, fixed["fn"], fixed["profile"])["surface_l2_error"]
        row["hertz_error_adaptive"] = hertz_errors(2, adaptive["fn"], adaptive["profile"])["surface_l2_error"]
    rows.append(row)

fields = ["scene", "newton_fixed", "newton_adaptive", "steps_fixed", "steps_adaptive", "wall_fixed_s",
          "wall_adaptive_s", "estimated_relative_error", "pressure_difference", "normal_force_difference",
          "tangential_force_difference", "hertz_error_fixed", "hertz_error_adaptive"]
csv_path = tool_cli.destination(args, "adaptive_stopping.csv")
with open(csv_path, "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(r for r in rows if not r["failed"])

lines = ["# Adaptive stopping of the Newton iteration", "",
         f"`Nonlinear solver/Stopping = adaptive` with `Adaptive stopping fraction` {args.fraction:g} against "
         "the fixed tolerance (`Newton/Tolerance` 1e-8, scaled residual), each scene as shipped "
         "(doc/formulation.md, \"Adaptive stopping\"). Differences: of the last load step, between the two "
         "runs, relative to the fixed run's largest contact pressure and its forces.", "",
         "| scene | Newton it. fixed | adaptive | load steps fixed / adaptive | wall (s) fixed | adaptive "
         "| estimated relative error | pressure difference | F_n difference | F_t difference |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
for r in rows:
    if r["failed"]:
        lines.append(f"| {r['scene']} | failed | | | | | | | | |")
        continue
    lines.append(f"| {r['scene']} | {r['newton_fixed']} | {r['newton_adaptive']} | "
                 f"{r['steps_fixed']} / {r['steps_adaptive']} | {r['wall_fixed_s']:.2f} | "
                 f"{r['wall_adaptive_s']:.2f} | {r['estimated_relative_error']:.3f} | "
                 f"{r['pressure_difference']:.1e} | {r['normal_force_difference']:.1e} | "
                 f"{r['tangential_force_difference']:.1e} |")
hertz = [r for r in rows if not r["failed"] and "hertz_error_fixed" in r]
for r in hertz:
    lines += ["", f"{r['scene']}: L2 error of the pressure against the closed form {r['hertz_error_fixed']:.5f} "
              f"(fixed), {r['hertz_error_adaptive']:.5f} (adaptive)."]
command = "contrib/benchmark_adaptive_stopping.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
lines += ["", f"Generated by `{command}` ({2 * len(SCENES)} runs, {args.jobs} at a time, one MPI rank each, "
          f"2-core machine: {total / 60:.1f} min).", ""]
md_path = tool_cli.destination(args, "adaptive_stopping.md")
with open(md_path, "w") as f:
    f.write("\n".join(lines))
print(f"table in {tool_cli.shown(md_path)}, {tool_cli.shown(csv_path)} ({total:.0f} s)")
sys.exit(1 if any(r["failed"] for r in rows) else 0)
