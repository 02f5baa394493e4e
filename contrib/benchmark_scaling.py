#!/usr/bin/python3
"""Scaling study: strong scaling on 1 and 2 ranks, the partitions of more ranks, and a model that
projects the time and memory of a Newton iteration to 10^3 ranks and 10^8 DoFs.

Usage: contrib/benchmark_scaling.py --executable build/stabilized_lagrangian [--workdir DIR]
                                    [--quick] [--output FOLDER | --doc]

1. Costs (one run at a time, one BLAS thread per rank, nothing else running): prm/hertz_sphere.prm
   (3D, Q1/P1, rigid plane) with `Linear solver/Method = iterative` at Global refinements 1, 2, 3
   on one rank, and 2, 3 on two ranks. Per Newton iteration, from run_summary.csv: assembly, AMG
   set-up, the Schur complement's forming and factorisation, GMRES (and the Schur solves in it),
   GMRES iterations; peak memory of the largest rank.
2. Partitions (2, 4 and 8 ranks oversubscribed on this machine's cores, so their times are not
   used): the largest rank's owned DoFs and ghost DoFs, and the GMRES iterations per solve as the
   AMG aggregates per rank; and ironing (prm/ironing.prm, the first 16 steps, two bodies) with the
   distributed and the replicated contact search: the master faces the busiest rank holds.
3. The model (written out in the output, with its assumptions): per-rank work from the one-rank
   fits at the per-rank size n = N / P, GMRES iterations from the fits in N and P, halo exchanges
   from the measured ghost layer, reductions and the gathers of the serial Schur solve from an
   assumed network (latency, bandwidth), projected to P = 10^3 and N = 10^8; which part stops
   scaling first.
--quick: refinements 1 and 2 only (the model is then fitted on two sizes); --reuse: the runs
already in the work directory. Writes scaling.md
(between marker comments, the text after them kept) into the --output folder (default: the work
directory; doc/ with --doc)."""
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
parser.add_argument("--workdir", default="/tmp/benchmark_scaling", help="where the runs are (default: %(default)s)")
parser.add_argument("--quick", action="store_true", help="refinements 1 and 2 only")
parser.add_argument("--reuse", action="store_true",
                    help="take the runs already in the work directory (their run_summary.csv) instead of "
                         "running them again")
tool_cli.add_output_arguments(parser, None, ["scaling.md"])
args = tool_cli.parse_with_workdir(parser)
workdir = os.path.abspath(args.workdir)
executable = os.path.abspath(args.executable)

HERTZ = robustness_map.read_scene(os.path.join(tool_cli.ROOT, "prm", "hertz_sphere.prm"))
IRONING = robustness_map.read_scene(os.path.join(tool_cli.ROOT, "prm", "ironing.prm"))
GLOBAL = "set Global refinements      = 2"
if GLOBAL not in HERTZ:
    raise SystemExit(f"prm/hertz_sphere.prm has no '{GLOBAL}'")
ITERATIVE = robustness_map.nested_set("Linear solver/Method", "iterative")
refinements = (1, 2) if args.quick else (1, 2, 3)
# Assumed network of a cluster (the model's only constants not measured here): latency of a
# message and of each stage of a reduction, and bandwidth per rank.
LATENCY_S = 2e-6
BANDWIDTH_B_PER_S = 5e9
# halo exchanges per GMRES iteration: the matrix-vector product and one V-cycle (two smoothing
# sweeps before and after and a residual on each of about four levels)
HALO_EXCHANGES_PER_ITERATION = 1 + 4 * 5
NEIGHBOURS_3D = 26


def run(name, text, ranks):
    """Run a scene on `ranks` ranks in workdir/name; its run_summary.csv row, or None."""
    case = os.path.join(workdir, name)
    path = os.path.join(case, "output", "run_summary.csv")
    if not (args.reuse and os.path.exists(path)):
        row = robustness_map.run_case(executable, text + robustness_map.OUTPUT_SECTION, case, None,
                                      robustness_map.Running(), ranks)
        print(f"{name}: {row['outcome']}, {row['wall_time_s']:.0f} s", flush=True)
        if row["outcome"] != "converged":
            return None
    return run_output.read_csv(path)[0]


def hertz(refinement):
    return HERTZ.replace(GLOBAL, f"set Global refinements      = {refinement}") + ITERATIVE


def fit(points):
    """Least-squares (c, e) of y = c x^e on log-log axes."""
    xs, ys = [math.log(x) for x, _ in points], [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    e = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return math.exp(my - e * mx), e


def per_newton(s):
    """Per Newton iteration (s) of a run's phases, and its sizes."""
    newton = s["newton_iterations"]
    return {"dofs": s["displacement_dofs"] + s["multiplier_dofs"], "multipliers": s["multiplier_dofs"],
            "owned": s["owned_dofs_max"], "owned_min": s["owned_dofs_min"], "ghosts": s["ghost_dofs_max"], "newton": newton,
            "assembly": s["assembly_s"] / newton, "amg": s["amg_setup_s"] / newton,
            "schur": s["schur_complement_s"] / newton,
            "gmres": (s["gmres_s"] - s["schur_solves_s"]) / newton,
            "schur_solves": s["schur_solves_s"] / newton, "krylov": s["krylov_iterations"] / newton,
            "linear": s["linear_solve_s"] / newton, "memory": s["peak_memory_MiB"],
            "blocks": s.get("schur_node_blocks", 0),
            "wall": s["wall_time_s"]}


# --- 1. costs --------------------------------------------------------------------------
costs = {}
for ranks, levels in ((1, refinements), (2, refinements[1:])):
    for refinement in levels:
        s = run(f"hertz-{refinement}-{ranks}rank", hertz(refinement), ranks)
        if s is not None:
            costs[(refinement, ranks)] = per_newton(s)

# --- 2. partitions ---------------------------------------------------------------------
largest = refinements[-1]
partitions = {}
for ranks in (2, 4, 8):
    s = run(f"partition-{largest}-{ranks}ranks", hertz(largest), ranks)
    if s is not None:
        partitions[ranks] = per_newton(s)
IRONING_SHORT = IRONING + robustness_map.nested_set("Load stepping/End time", 0.4) + \
    robustness_map.nested_set("Load stepping/Number of load steps", 16)
holdings = {}
for ranks in (2, 4, 8):
    for mode in ("distributed", "replicated"):
        s = run(f"ironing-{mode}-{ranks}ranks",
                IRONING_SHORT + robustness_map.nested_set("Contact/Master surface search", mode), ranks)
        if s is not None:
            holdings[(ranks, mode)] = (s["master_faces_held_max"], s["master_faces"], s["master_search_growths"],
                                       s["newton_iterations"])

# --- 3. the model ----------------------------------------------------------------------
one_rank = [costs[(r, 1)] for r in refinements if (r, 1) in costs]
if len(one_rank) < 2:
    raise SystemExit("fewer than two one-rank runs converged: no model")
fits = {key: fit([(c["dofs"], c[key]) for c in one_rank]) for key in ("assembly", "amg", "krylov")}


def linear_fit(points):
    """Least-squares (a, b) of y = a + b x."""
    mx, my = sum(x for x, _ in points) / len(points), sum(y for _, y in points) / len(points)
    b = sum((x - mx) * (y - my) for x, y in points) / sum((x - mx) ** 2 for x, _ in points)
    return my - b * mx, b


# memory: what every process holds (libraries, MPI) plus a share per DoF
memory_fit = linear_fit([(c["dofs"], c["memory"]) for c in one_rank])
# the per-iteration cost of GMRES (without the Schur solves) per DoF
gmres_per_iteration = fit([(c["dofs"], c["gmres"] / c["krylov"]) for c in one_rank])
multipliers = fit([(c["dofs"], c["multipliers"]) for c in one_rank])
schur_factorisation = fit([(c["multipliers"], c["schur"]) for c in one_rank])
# Ŝ in node blocks each rank inverts (rigid partner, nodal quadrature), or gathered and
# factorised on one rank
local_schur = all(c["blocks"] > 0 for c in one_rank)
schur_solve = fit([(c["multipliers"], c["schur_solves"] / (c["krylov"] + 1)) for c in one_rank])
# the ghost layer of a 3D partition: a surface, g n^(2/3) (g from the partitions)
ghosts = (sum(p["ghosts"] / p["owned"] ** (2 / 3) for p in partitions.values()) / len(partitions), 2 / 3) \
    if partitions else None
# GMRES iterations against the rank count at the largest mesh (the AMG aggregates per rank)
krylov_at = {1: costs[(largest, 1)]["krylov"]} if (largest, 1) in costs else {}
krylov_at.update({p: c["krylov"] for p, c in partitions.items()})
rank_growth = fit([(p, k / krylov_at[1]) for p, k in krylov_at.items() if p > 1]) \
    if 1 in krylov_at and len(krylov_at) > 2 else (1., 0.)


def value(f, x):
    return f[0] * x ** f[1]


SCHUR_SET_UP = "Schur set-up (node blocks, per rank)" if local_schur else "Schur factorisation (serial)"
SCHUR_SOLVES = "Schur solves (node blocks, per rank)" if local_schur else "Schur solves (serial)"


def model(N, P):
    """Seconds per Newton iteration on the largest rank, by part, and its memory (MiB)."""
    n = N / P
    n_m = value(multipliers, N)
    k = value(fits["krylov"], N) * value(rank_growth, P) if P > 1 else value(fits["krylov"], N)
    halo = 0.
    if P > 1 and ghosts is not None:
        volume = value(ghosts, n) * 8 * 2
        halo = HALO_EXCHANGES_PER_ITERATION * (volume / BANDWIDTH_B_PER_S + NEIGHBOURS_3D * LATENCY_S)
    # modified Gram-Schmidt: about min(k, 100) / 2 + 2 reductions per GMRES iteration
    reductions = (min(k, 100) / 2 + 2) * LATENCY_S * math.log2(P) if P > 1 else 0.
    if local_schur:
        # each rank inverts the blocks of its own nodes
        m_rank, gather = n_m / P, 0.
    else:
        # one rank factorises and solves; the right-hand side gathered from and the solution
        # scattered to every rank
        m_rank = n_m
        gather = 2 * (n_m * 8 / BANDWIDTH_B_PER_S + (P - 1) * LATENCY_S) if P > 1 else 0.
    parts = {"assembly": value(fits["assembly"], n), "AMG set-up": value(fits["amg"], n),
             SCHUR_SET_UP: value(schur_factorisation, m_rank),
             "GMRES work": k * value(gmres_per_iteration, n),
             SCHUR_SOLVES: (k + 1) * (value(schur_solve, m_rank) + gather),
             "halo exchanges": k * halo, "reductions": k * reductions}
    return parts, memory_fit[0] + memory_fit[1] * n, k, n_m


def total(parts):
    return sum(parts.values())


BEGIN = "<!-- written by contrib/benchmark_scaling.py: begin -->"
END = "<!-- written by contrib/benchmark_scaling.py: end -->"
lines = [BEGIN, "## Scaling of a Newton iteration", "",
         f"Generated by `contrib/benchmark_scaling.py --doc{' --quick' if args.quick else ''}`: the 3D Hertz "
         "sphere (`prm/hertz_sphere.prm`, Q1/P1, rigid plane, one load step) with `Linear solver/Method = "
         "iterative`. Times per Newton iteration from run_summary.csv (the slowest rank's); one BLAS thread "
         "per rank, one run at a time.", "",
         "### 1. Measured: one and two ranks", "",
         "| refinement | ranks | DoFs | owned (largest rank) | ghosts | GMRES per solve | assembly (s) | "
         "AMG set-up (s) | Schur form + factorise (s) | GMRES without Schur solves (s) | Schur solves (s) | "
         "linear solve (s) | peak memory (MiB) |",
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
for (refinement, ranks), c in sorted(costs.items()):
    lines.append(f"| {refinement} | {ranks} | {c['dofs']:.0f} | {c['owned']:.0f} | {c['ghosts']:.0f} | "
                 f"{c['krylov']:.1f} | {c['assembly']:.3f} | {c['amg']:.3f} | {c['schur']:.4f} | "
                 f"{c['gmres']:.3f} | {c['schur_solves']:.4f} | {c['linear']:.3f} | {c['memory']:.0f} |")
lines.append("")
for refinement in refinements[1:]:
    if (refinement, 1) in costs and (refinement, 2) in costs:
        a, b = costs[(refinement, 1)], costs[(refinement, 2)]
        one, two = a["assembly"] + a["linear"], b["assembly"] + b["linear"]
        lines.append(f"- Refinement {refinement} ({a['dofs']:.0f} DoFs): assembly + linear solve per Newton "
                     f"iteration {one:.3f} s on one rank, {two:.3f} s on two: speed-up {one / two:.2f}.")
lines += ["", "### 2. Partitions of more ranks (oversubscribed: sizes and iterations, not times)", "",
          "| ranks | DoFs | owned (largest rank) | owned (smallest) | ghosts (largest) | GMRES per solve |",
          "|---:|---:|---:|---:|---:|---:|"]
for ranks, c in sorted(partitions.items()):
    lines.append(f"| {ranks} | {c['dofs']:.0f} | {c['owned']:.0f} | {c['owned_min']:.0f} | {c['ghosts']:.0f} | "
                 f"{c['krylov']:.1f} |")
lines += ["", "Ironing (two bodies, first 16 load steps) — master faces held by the busiest rank:", "",
          "| ranks | distributed search | replicated search | growths (distributed) | Newton iterations (both) |",
          "|---:|---:|---:|---:|---|"]
for ranks in (2, 4, 8):
    d, r = holdings.get((ranks, "distributed")), holdings.get((ranks, "replicated"))
    if d and r:
        lines.append(f"| {ranks} | {d[0]:.0f} of {d[1]:.0f} | {r[0]:.0f} of {r[1]:.0f} | {d[2]:.0f} | "
                     f"{d[3]:.0f}, {r[3]:.0f} |")
lines += ["", "### 3. Model", "",
          "Fits on the one-rank runs (N: DoFs; n = N / P per rank):", "",
          f"- assembly per Newton iteration {fits['assembly'][0]:.3g} n^{fits['assembly'][1]:.2f} s; AMG set-up "
          f"{fits['amg'][0]:.3g} n^{fits['amg'][1]:.2f} s; GMRES work per iteration "
          f"{gmres_per_iteration[0]:.3g} n^{gmres_per_iteration[1]:.2f} s;",
          f"- GMRES iterations per solve {fits['krylov'][0]:.3g} N^{fits['krylov'][1]:.2f}, times "
          f"{rank_growth[0]:.3g} P^{rank_growth[1]:.2f} on P ranks (section 2);",
          f"- multipliers {multipliers[0]:.3g} N^{multipliers[1]:.2f}; the Schur complement's set-up "
          f"{schur_factorisation[0]:.3g} m^{schur_factorisation[1]:.2f} s and one solve with it "
          f"{schur_solve[0]:.3g} m^{schur_solve[1]:.2f} s (m multipliers; " +
          ("inverted in the nodes' blocks, by the rank that owns them, so m is the rank's share);"
           if local_schur else "KLU, serial: Amesos gathers Ŝ onto one rank);"),
          (f"- ghost DoFs of the largest rank {ghosts[0]:.3g} n^{ghosts[1]:.2f} (section 2);" if ghosts else
           "- ghost DoFs: no partition runs;"),
          f"- peak memory per rank {memory_fit[0]:.0f} MiB + {memory_fit[1] * 1e3:.3g} MiB per 10^3 DoFs of its "
          "share.",
          "",
          f"Assumed network (not measured here): latency {LATENCY_S * 1e6:.0f} µs per message and per "
          f"reduction stage, {BANDWIDTH_B_PER_S / 1e9:.0f} GB/s per rank; {HALO_EXCHANGES_PER_ITERATION} halo "
          f"exchanges per GMRES iteration with {NEIGHBOURS_3D} neighbours; log2 P stages per reduction, "
          "min(k, 100) / 2 + 2 reductions per GMRES iteration (modified Gram–Schmidt); where Ŝ is factorised "
          "whole on one rank, each of its solves gathers the right-hand side from every rank and scatters the "
          "solution (2 (P − 1) messages).", ""]
header = ["N", "P", "n per rank", "GMRES per solve", "multipliers"]
projections = [(c["dofs"], r) for (ref, r), c in sorted(costs.items()) if ref == largest] + \
    [(1e6, 8), (1e7, 100), (1e8, 1000), (1e8, 4000)]
parts_names = list(model(1e6, 8)[0].keys())
lines += ["| " + " | ".join(header + [f"{p} (s)" for p in parts_names] + ["total (s)", "measured (s)",
                                                                         "memory per rank (MiB)"]) + " |",
          "|" + "---:|" * (len(header) + len(parts_names) + 3)]
for N, P in projections:
    parts, memory, k, n_m = model(N, P)
    measured = ""
    for (ref, r), c in costs.items():
        if r == P and abs(c["dofs"] - N) < 1:
            measured = f"{c['assembly'] + c['linear']:.3f}"
    lines.append(f"| {N:.3g} | {P} | {N / P:.3g} | {k:.0f} | {n_m:.3g} | " +
                 " | ".join(f"{v:.3g}" for v in parts.values()) + f" | {total(parts):.3g} | {measured} | "
                 f"{memory:.0f} |")
share = {}
for N, P in ((1e8, 1000), (1e8, 4000)):
    parts, _, _, _ = model(N, P)
    share[P] = (parts[SCHUR_SET_UP] + parts[SCHUR_SOLVES]) / total(parts)
worst = max(model(1e8, 1000)[0].items(), key=lambda item: item[1])
lines += ["", f"- At N = 10^8 on 10^3 ranks the largest part is {worst[0]} ({worst[1]:.3g} s of "
          f"{total(model(1e8, 1000)[0]):.3g} s per Newton iteration); the Schur complement "
          f"({'node blocks' if local_schur else 'serial'}) takes {100 * share[1000]:.0f} % of it, "
          f"{100 * share[4000]:.0f} % on 4·10^3 ranks.", "", END]
path = tool_cli.destination(args, "scaling.md")
robustness_map.write_section(path, BEGIN, END, "\n".join(lines))
print(f"wrote {path}")
