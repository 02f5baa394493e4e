#!/usr/bin/python3
"""Accuracy against cost of the finite element pairs on Hertz problems.

Usage: contrib/benchmark_hertz.py --executable build/stabilized_lagrangian
                                  [--workdir DIR] [--quick] [--output FOLDER | --doc]

Runs prm/hertz_cylinder.prm (2D, frictionless half cylinder on a rigid plane,
the whole load in one step from rest) and prm/hertz_sphere.prm (3D) for every
FE pair and several local refinements of the contact zone, and with adaptive
refinement around the active set, and writes into the --output folder
(default: the work directory; doc/ with --doc):

  benchmark_hertz.csv   one row per run: pair, mesh, DoFs, Newton iterations,
                        wall / solve / assembly time, errors
  benchmark_hertz.md    the tables, the observed convergence orders, the cost
                        per Newton iteration and its split, the log-log slope
                        of the direct solver's cost
  benchmark_hertz_error_dofs.png, benchmark_hertz_pareto.png,
  benchmark_hertz_profiles.png

Errors are against the closed form of Hertz computed with the run's own
normal force P (contrib/hertz_errors.py: half-width, peak nodal pressure,
relative L2 error of the nodal pressure profile). The closed form is for a
half-space: the finite cylinder and ball differ from it by
O((a/R)^2), so the indentation is chosen small (2D: 0.25 mm, a/R ~ 0.035;
3D: 1 mm, a/R ~ 0.1, which a coarser 3D mesh can still resolve)."""
import argparse
import csv
import math
import os
import subprocess

import sys

import matplotlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_output  # noqa: E402
import tool_cli  # noqa: E402
from hertz_errors import hertz_errors, hertz_scene  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", required=True, type=tool_cli.executable)
parser.add_argument("--workdir", default="/tmp/benchmark_hertz", help="where the runs are (default: %(default)s)")
parser.add_argument("--quick", action="store_true", help="fewer meshes (a smoke test of the script)")
tool_cli.add_output_arguments(parser, None, ["benchmark_hertz.{csv,md}", "the plots"])
args = parser.parse_args()
args.output = args.output or args.workdir
tool_cli.check_output(parser, args)
executable = args.executable
E, nu = 200000.0, 0.3
E_star = E / (1 - nu * nu)
R = 100.0


def read_csv(path):
    return run_output.read_csv(path)


def run(dim, pair, local, cycles=0, delta=None, null_pivots=False, profile_name=None, criterion="active set"):
    text = hertz_scene(dim, pair, local, delta) + f"""
subsection Adaptive refinement
  set Cycles = {cycles}
  set Criterion = {criterion}
end
subsection Linear solver
  set Null pivot detection = {'true' if null_pivots else 'false'}
end
subsection Output
  set Output directory = output
  set Write vtu = false
end
"""
    workdir = os.path.join(args.workdir, f"{dim}d-{pair.replace('/', '').replace(' ', '_')}-{local}-{cycles}"
                           f"-{criterion.replace(' ', '_')}")
    os.makedirs(workdir, exist_ok=True)
    with open(os.path.join(workdir, "input.prm"), "w") as f:
        f.write(text)
    result = subprocess.run([executable, "input.prm"], cwd=workdir, capture_output=True, text=True)
    if result.returncode != 0:
        print(f"  {dim}D {pair} local {local} cycles {cycles}: exit code {result.returncode}")
        return None
    out = os.path.join(workdir, "output")
    summary = read_csv(os.path.join(out, "run_summary.csv"))[0]
    P = read_csv(os.path.join(out, "statistics.csv"))[-1]["normal_force_N"]
    profiles = sorted(p for p in os.listdir(out) if p.startswith("profile-"))
    profile = read_csv(os.path.join(out, profiles[-1]))
    errors = hertz_errors(dim, P, profile)
    cycle_time = summary["wall_time_s"]
    if cycles > 0:  # the time of every mesh of the adaptive sequence
        cycle_time = sum(r["wall_time_s"] for r in read_csv(os.path.join(out, "refinement_cycles.csv")))
    row = {"dim": dim, "pair": pair, "local_refinements": local, "adaptive_cycles": cycles,
           "refinement": "uniform contact zone" if cycles == 0 else criterion,
           "dofs": int(summary["displacement_dofs"] + summary["multiplier_dofs"]),
           "multiplier_dofs": int(summary["multiplier_dofs"]),
           "newton_iterations": int(summary["newton_iterations"]),
           "wall_time_s": cycle_time, "solve_time_s": summary["linear_solve_s"],
           "assembly_time_s": summary["assembly_s"], **errors}
    if profile_name:
        row["profile"] = profile
    print(f"  {dim}D {pair:13s} local {local} cycles {cycles}: {row['dofs']:7d} DoFs, "
          f"{row['newton_iterations']} Newton, {row['wall_time_s']:.2f} s, h = {errors['h_mm']:.3f}, "
          f"a {errors['half_width_error']:.2%}, p0 {errors['peak_error']:.2%}, L2 {errors['l2_error']:.2%}")
    return row


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


delta2, delta3 = 0.25, 1.0
rows = []
print("2D cylinder")
pairs2 = ["Q1/P1", "Q2/P1", "Q2/P2", "Q1/P1 coarse", "Q1/P0"]
locals2 = [3, 4, 5] if args.quick else [3, 4, 5, 6, 7]
for pair in pairs2:
    for local in locals2:
        if pair.startswith("Q2") and local > 6:
            continue
        row = run(2, pair, local, delta=delta2)
        if row:
            rows.append(row)
for pair in ("Q1/P1", "Q2/P1"):
    for cycles in ([1] if args.quick else [1, 2, 3]):
        row = run(2, pair, 3, cycles=cycles, delta=delta2)
        if row:
            rows.append(row)
    for cycles in ([3] if args.quick else [3, 4, 5, 6, 7]):
        if pair == "Q2/P1" and cycles > 6:
            continue
        row = run(2, pair, 2, cycles=cycles, delta=delta2, criterion="Kelly")
        if row:
            rows.append(row)
print("3D sphere")
for pair in ("Q1/P1", "Q2/P1", "Q1/P1 coarse"):
    for local in ([2, 3] if args.quick else [1, 2, 3]):
        if pair == "Q2/P1" and local > 2:
            continue  # 196k DoFs: 4 minutes of 3D Q2 factorisations
        row = run(3, pair, local, delta=delta3)
        if row:
            rows.append(row)
for cycles in ([1] if args.quick else [1, 2]):
    row = run(3, "Q1/P1", 2, cycles=cycles, delta=delta3)
    if row:
        rows.append(row)
for cycles in ([2] if args.quick else [2, 3, 4]):
    row = run(3, "Q1/P1", 1, cycles=cycles, delta=delta3, criterion="Kelly")
    if row:
        rows.append(row)

# profiles of a stable and an unstable pair on the same mesh
stable = run(2, "Q1/P1", 5, delta=delta2, profile_name=True)
unstable = run(2, "Q1/P0", 5, delta=delta2, profile_name=True)
singular = run(2, "Q1/P2", 5, delta=delta2, null_pivots=True, profile_name=True)

fields = ["dim", "pair", "refinement", "local_refinements", "adaptive_cycles", "dofs", "multiplier_dofs", "newton_iterations",
          "wall_time_s", "solve_time_s", "assembly_time_s", "h_mm", "a_mm", "a_hertz_mm", "half_width_error",
          "peak_error", "l2_error"]
with open(tool_cli.destination(args, "benchmark_hertz.csv"), "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)


def series(dim, pair, refinement):
    return [r for r in rows if r["dim"] == dim and r["pair"] == pair and r["refinement"] == refinement]


refinements = ("uniform contact zone", "active set", "Kelly")


# plots: error against DoFs and against seconds (Pareto)
for kind, xkey, xlabel in (("error_dofs", "dofs", "DoFs"), ("pareto", "wall_time_s", "wall time (s)")):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, dim in zip(axes, (2, 3)):
        for pair in pairs2:
            for refinement, style in zip(refinements, ("o-", "s--", "^:")):
                s = series(dim, pair, refinement)
                if s:
                    ax.loglog([r[xkey] for r in s], [r["l2_error"] for r in s], style,
                              label=pair + ("" if refinement == refinements[0] else ", adaptive " + refinement))
        ax.axhline(0.01, color="grey", lw=0.8, ls=":")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("relative L2 error of the pressure" + (" (nodal RMS)" if dim == 3 else ""))
        ax.set_title("2D Hertz cylinder" if dim == 2 else "3D Hertz sphere")
        handles, labels = ax.get_legend_handles_labels()
        unique = dict(zip(labels, handles))
        ax.legend(unique.values(), unique.keys(), fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(tool_cli.destination(args, f"benchmark_hertz_{kind}.png"), dpi=110)
    plt.close(fig)

fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
for ax, row, title in zip(axes, (stable, unstable, singular),
                          ("Q1/P1 (stable)", "Q1/P0 (unstable: beta_h -> 0)", "Q1/P2 (beta_h = 0, null pivots)")):
    if not row:
        ax.set_title(title + ": failed")
        continue
    xs = [p["x_mm"] for p in row["profile"]]
    ps = [p["contact_pressure_MPa"] for p in row["profile"]]
    a_h = row["a_hertz_mm"]
    p0_h = a_h * E_star / (2 * R)  # 2P/(pi a) with a^2 = 4PR/(pi E*)
    ax.plot(xs, ps, ".-", lw=0.8, label="computed (nodes)")
    grid = [x / 200 * 2 * a_h - a_h for x in range(201)]
    ax.plot(grid, [p0_h * math.sqrt(max(0, 1 - (x / a_h) ** 2)) for x in grid], "k-", lw=1, label="Hertz")
    ax.set_xlim(-1.6 * a_h, 1.6 * a_h)
    ax.set_title(title)
    ax.set_xlabel("x (mm)")
    ax.legend(fontsize=8)
axes[0].set_ylabel("contact pressure (MPa)")
fig.tight_layout()
fig.savefig(tool_cli.destination(args, "benchmark_hertz_profiles.png"), dpi=110)
plt.close(fig)

# the markdown page
lines = ["# Hertz: accuracy against cost of the finite element pairs", "",
         "Generated by `contrib/benchmark_hertz.py --executable build/stabilized_lagrangian --doc` "
         "(1 MPI rank, 2-core machine, MUMPS). Frictionless, the whole load in one step from rest, "
         f"indentation {delta2} mm (a/R ~ {rows[0]['a_hertz_mm'] / R:.3f} in 2D). "
         "Errors against Hertz with the run's own force; see the script's header for the measures.", ""]
for dim in (2, 3):
    lines += [f"## {'2D cylinder (plane strain)' if dim == 2 else '3D sphere'}", "",
              "| pair | refinement | local ref. | adaptive cycles | DoFs | Newton | wall (s) | solve (s) "
              "| assembly (s) | h (mm) | half-width err. | peak err. | L2 err. |",
              "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if r["dim"] == dim:
            lines.append(f"| {r['pair']} | {r['refinement']} | {r['local_refinements']} | {r['adaptive_cycles']} | "
                         f"{r['dofs']} | "
                         f"{r['newton_iterations']} | {r['wall_time_s']:.2f} | {r['solve_time_s']:.2f} | "
                         f"{r['assembly_time_s']:.2f} | {r['h_mm']:.3f} | {r['half_width_error']:.2%} | "
                         f"{r['peak_error']:.2%} | {r['l2_error']:.2%} |")
    lines.append("")
    lines += ["Observed orders (least-squares slope of log error against log h over the uniform meshes):", "",
              "| pair | half-width | peak | L2 |", "|---|---:|---:|---:|"]
    for pair in pairs2:
        s = series(dim, pair, refinements[0])
        if len(s) >= 3:
            hs = [r["h_mm"] for r in s]
            orders = []
            for key in ("half_width_error", "peak_error", "l2_error"):
                ys = [max(r[key], 1e-12) for r in s]
                orders.append(f"{slope(hs, ys):.2f}")
            lines.append(f"| {pair} | " + " | ".join(orders) + " |")
    lines.append("")
    lines += ["Cost per Newton iteration at the largest mesh of each pair, and the log-log slope of the "
              "solve time against DoFs (direct solver):", "",
              "| pair | DoFs | per Newton it. (s) | solve / it. | assembly / it. | solve-time slope |",
              "|---|---:|---:|---:|---:|---:|"]
    for pair in pairs2:
        s = series(dim, pair, refinements[0])
        if len(s) >= 2:
            big = s[-1]
            n = big["newton_iterations"]
            per = (big["solve_time_s"] + big["assembly_time_s"]) / n
            slope_solve = slope([r["dofs"] for r in s], [max(r["solve_time_s"], 1e-6) for r in s])
            lines.append(f"| {pair} | {big['dofs']} | {per:.3f} | {big['solve_time_s'] / n:.3f} | "
                         f"{big['assembly_time_s'] / n:.3f} | {slope_solve:.2f} |")
    lines.append("")
lines += ["![error against DoFs](benchmark_hertz_error_dofs.png)", "",
          "![error against wall time](benchmark_hertz_pareto.png)", "",
          "![stable and unstable pressure profiles](benchmark_hertz_profiles.png)", ""]
markdown = tool_cli.destination(args, "benchmark_hertz.md")
with open(markdown, "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"wrote {os.path.dirname(markdown)}/benchmark_hertz.{{md,csv}} and the plots")
