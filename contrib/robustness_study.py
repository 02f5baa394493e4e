#!/usr/bin/python3
"""Robustness study of the augmentation parameters r_n, r_t: maps, scaling with E, mu, h, automatic values.

Usage: contrib/robustness_study.py --executable build/stabilized_lagrangian
           [--part maps|scaling|automatic|all] [--jobs N] [--timeout SECONDS] [--workdir DIR]
           [--output FOLDER | --doc]

Three parts, each writing its data and plots into the results folder (--output,
default the work directory; doc/ with --doc) and its own section of
robustness_results.md there (the sections of the parts not run are kept):

maps       for prm/patin_{elastic,neo_hookean,elastoplastic}.prm, the nested fixed
           point and the generalized Newton maps (contrib/robustness_map.py) on
           r_n = 1e1..1e13 (9 log points) x r_t = 1e-4..1e6 (11), with Maximum step
           cuts = 0 (a failed step is a divergence, as in the seed paper) and
           Maximum Newton iterations per load step = 300. Writes
           robustness_<scene>_{nested,newton}.csv and robustness_<scene>.png
           (both maps side by side, one colour scale), and per map I1 x I2 and the
           fewest mean Newton iterations per load step.
scaling    on the elastic patin, for both algorithms and the configurations
           (Global refinements, E, mu) = (3|4|5, 2e5, 0.1), (4, 2e4, 0.1), (4, 2e5, 0.3)
           (h = 50 / 2^refinements mm), 1D sweeps of r_n = 1e0..1e14 at r_t = 1 and
           of r_t = 1e-5..1e8 at r_n = 1e4, 2 points per decade, same cuts and
           Newton budget as the maps. r_max (r_min) is the largest (smallest)
           converged value before the first failure above (below) the value with
           the fewest iterations. Writes robustness_scaling.csv (one row per
           configuration, algorithm and swept parameter, with C = r_max h / E for
           r_n, r_max h / mu for r_t) and robustness_scaling.png.
automatic  r_n = r_t = automatic with both Automatic factors = f, f = 1e-6..1e12, for
           the three patin scenes and prm/hertz_cylinder.prm, both algorithms,
           the scenes' step cuts and Newton budget as shipped. Writes
           robustness_automatic.csv and the worst/best ratio of the mean
           iterations over f in [1e-4, 1e4].

Every case runs in its own directory under WORKDIR (default /tmp/robustness_study),
with its input.prm and log.txt. The script exits with 1 if a case ended in error
(an exit code other than 0 and 2), timeout or wrote a NaN: those are bugs, listed
in the markdown with their paths; a divergence is not."""
import argparse
import csv
import math
import os
import re
import shlex
import sys
import time

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_map  # noqa: E402
import tool_cli  # noqa: E402
from robustness_map import (build_scene, convergence_bounds, draw_map, log_grid, nested_set,  # noqa: E402
                            sweep, write_csv)

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
# the results folder and its page, set by main() from --output or --doc
results_folder = None
results_md = None
PARTS = ["maps", "scaling", "automatic"]
PATIN_SCENES = [("elastic", "elastic patin"), ("neo_hookean", "neo-Hookean patin"),
                ("elastoplastic", "J2 elasto-plastic patin")]
ALGORITHMS = ["nested", "newton"]
ALGORITHM_NAMES = dict(nested="nested fixed points", newton="generalized Newton")
NEWTON_BUDGET = "Nonlinear solver/Maximum Newton iterations per load step=300"

MAP_RN = (1e1, 1e13, 9)
MAP_RT = (1e-4, 1e6, 11)

# (Global refinements, E, mu) on the elastic patin: 100 mm in 2 x 2^refinements faces
SCALING_CONFIGS = [(3, 2e5, 0.1), (4, 2e5, 0.1), (5, 2e5, 0.1), (4, 2e4, 0.1), (4, 2e5, 0.3)]
SCALING_RN = (1e0, 1e14, 29)  # 2 points per decade
SCALING_RT = (1e-5, 1e8, 27)
SCALING_FIXED = dict(r_n=1.0, r_t=1e4)  # the fixed other parameter: r_t = 1 in the r_n sweep, r_n = 1e4 in the r_t one
SCALING_COLUMNS = ["refinements", "h_mm", "E_MPa", "mu", "algorithm", "parameter", "fixed_other", "converged",
                   "points", "best_value", "best_mean_newton_per_step", "r_min", "r_max", "C_min", "C_max",
                   "failures", "pattern"]

AUTOMATIC_SCENES = [("patin_elastic", "elastic patin"), ("patin_neo_hookean", "neo-Hookean patin"),
                    ("patin_elastoplastic", "J2 elasto-plastic patin"), ("hertz_cylinder", "Hertz cylinder")]
AUTOMATIC_FACTORS = [1e-6, 1e-4, 1e-2, 1e0, 1e2, 1e4, 1e6, 1e8, 1e10, 1e12]
AUTOMATIC_COLUMNS = ["scene", "algorithm", "factor", "r_n", "r_t", "outcome", "exit_code", "load_steps",
                     "newton_iterations", "mean_newton_per_step", "wall_time_s", "nan_in_output"]


def fmt(value, digits=3):
    return "–" if value is None else f"{value:.{digits}g}"


def is_bug(row):
    return row["outcome"] in ("error", "timeout") or row["nan_in_output"]


def bug_lines(rows_and_dirs):
    """Markdown lines listing the (row, case directory) that are bugs."""
    lines = []
    for row, case_dir in rows_and_dirs:
        if is_bug(row):
            what = row["outcome"] + (f" (exit code {row['exit_code']})" if row["outcome"] == "error" else "")
            if row["nan_in_output"]:
                what += ", NaN/inf in its output"
            lines.append(f"- **{what}**: `{os.path.join(case_dir, 'input.prm')}`, log "
                         f"`{os.path.join(case_dir, 'log.txt')}`")
    return lines


# ---------------------------------------------------------------------------------------------- maps

def map_case_dir(workdir, scene, algorithm, row):
    rn_values, rt_values = log_grid(*MAP_RN), log_grid(*MAP_RT)
    return os.path.join(workdir, "maps", scene, algorithm,
                        f"rn{rn_values.index(row['r_n']):02d}_rt{rt_values.index(row['r_t']):02d}")


def best_cells(rows):
    """The fewest mean iterations of the converged rows and the rows that reach it."""
    converged = [r for r in rows if r["outcome"] == "converged"]
    if not converged:
        return None, []
    best = min(r["mean_newton_per_step"] for r in converged)
    return best, [r for r in converged if r["mean_newton_per_step"] == best]


def run_maps(args):
    lines = []
    bugs = []
    for scene, title in PATIN_SCENES:
        scene_path = os.path.join(root, "prm", f"patin_{scene}.prm")
        maps = {}
        for algorithm in ALGORITHMS:
            print(f"== map: {scene}, {algorithm}", flush=True)
            start = time.monotonic()
            text = build_scene(scene_path, [NEWTON_BUDGET], algorithm, max_cuts=0)
            rows = sweep(args.executable, text, log_grid(*MAP_RN), log_grid(*MAP_RT),
                         os.path.join(args.workdir, "maps", scene, algorithm), args.jobs, args.timeout)
            write_csv(rows, os.path.join(results_folder, f"robustness_{scene}_{algorithm}.csv"))
            maps[algorithm] = (rows, time.monotonic() - start)
            bugs += [(r, map_case_dir(args.workdir, scene, algorithm, r)) for r in rows]
        # both maps on one colour scale: whole iterations over the converged cells of both
        means = [r["mean_newton_per_step"] for rows, _ in maps.values() for r in rows if r["outcome"] == "converged"]
        low, high = (math.floor(min(means)), math.ceil(max(means))) if means else (0, 1)
        norm = Normalize(low, max(high, low + 1))
        figure = Figure(figsize=(14, 5.8), layout="constrained")
        FigureCanvasAgg(figure)
        axes = figure.subplots(1, 2)
        for ax, algorithm in zip(axes, ALGORITHMS):
            mappable = draw_map(ax, maps[algorithm][0], f"{title}: {ALGORITHM_NAMES[algorithm]}", norm=norm)
        figure.colorbar(mappable, ax=list(axes), label="mean Newton iterations per load step")
        png = os.path.join(results_folder, f"robustness_{scene}.png")
        figure.savefig(png, dpi=120)

        lines += [f"### {title} (`prm/patin_{scene}.prm`)", "",
                  f"![{title}](robustness_{scene}.png)", "",
                  "| algorithm | converged / diverged / error+timeout | I1 (r_n, N/mm³) | I2 (r_t, 1/mm) "
                  "| fewest mean iterations | at (r_n, r_t) | most (converged) | time |",
                  "|---|---|---|---|---|---|---|---|"]
        for algorithm in ALGORITHMS:
            rows, seconds = maps[algorithm]
            counts = [sum(r["outcome"] == o for r in rows) for o in ("converged", "diverged")]
            counts.append(sum(r["outcome"] in ("error", "timeout") for r in rows))
            _, _, rectangle = convergence_bounds(rows)
            i1, i2 = (("none", "none") if rectangle is None else
                      tuple(f"[{fmt(lo, 2)}, {fmt(hi, 2)}]" for lo, hi in rectangle))
            best, where = best_cells(rows)
            at = ", ".join(f"({fmt(r['r_n'], 2)}, {fmt(r['r_t'], 2)})" for r in where[:4])
            if len(where) > 4:
                at += f" and {len(where) - 4} more"
            worst = max((r["mean_newton_per_step"] for r in rows if r["outcome"] == "converged"), default=None)
            lines.append(f"| {ALGORITHM_NAMES[algorithm]} | {' / '.join(map(str, counts))} | {i1} | {i2} "
                         f"| {fmt(best)} | {at or '–'} | {fmt(worst)} | {seconds:.0f} s |")
        lines += ["", "Converged r_n range per r_t (values in between may fail):", "",
                  "| r_t | " + " | ".join(ALGORITHM_NAMES[a] for a in ALGORITHMS) + " |",
                  "|---|" + "---|" * len(ALGORITHMS)]
        ranges = {a: convergence_bounds(maps[a][0])[0] for a in ALGORITHMS}
        for rt in log_grid(*MAP_RT):
            cells = [("none" if ranges[a][rt] is None else f"[{fmt(ranges[a][rt][0], 2)}, {fmt(ranges[a][rt][1], 2)}]")
                     for a in ALGORITHMS]
            lines.append(f"| {fmt(rt, 2)} | " + " | ".join(cells) + " |")
        lines.append("")
    header = [f"Grid: r_n = {fmt(MAP_RN[0])}..{fmt(MAP_RN[1])} ({MAP_RN[2]} log points) x "
              f"r_t = {fmt(MAP_RT[0])}..{fmt(MAP_RT[1])} ({MAP_RT[2]} log points); Load stepping/Maximum step "
              "cuts = 0 (a failed load step is a divergence, as in the seed paper), Nonlinear solver/Maximum "
              "Newton iterations per load step = 300. I1 x I2 is the largest all-converged rectangle of the grid "
              "(contrib/robustness_map.py convergence_bounds); the iteration counts are mean Newton iterations "
              "per load step (10 steps). Data: `robustness_<scene>_{nested,newton}.csv`, beside this page.", ""]
    return header + lines, bugs


# ------------------------------------------------------------------------------------------- scaling

def face_size(refinements):
    """h of the patin: 100 mm in 2 x 2^refinements contact faces."""
    return 100.0 / (2 * 2 ** refinements)


def sweep_bounds(rows, parameter):
    """(best row, r_min, r_max) of a 1D sweep over parameter ('r_n' or 'r_t'): the converged values next to the
    fewest-iteration one up to the first failure below (r_min) and above (r_max); None if the range ends first.
    Ties on the fewest iterations: the smallest value. best row None if nothing converged."""
    rows = sorted(rows, key=lambda r: r[parameter])
    ok = [r["outcome"] == "converged" for r in rows]
    if not any(ok):
        return None, None, None
    ib = min((i for i in range(len(rows)) if ok[i]), key=lambda i: (rows[i]["mean_newton_per_step"], i))
    hi = ib
    while hi + 1 < len(rows) and ok[hi + 1]:
        hi += 1
    lo = ib
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    r_max = rows[hi][parameter] if hi + 1 < len(rows) else None
    r_min = rows[lo][parameter] if lo > 0 else None
    return rows[ib], r_min, r_max


def pattern(rows, parameter):
    """The outcomes of a 1D sweep from its smallest value up: + converged, . diverged, E error or timeout."""
    symbols = dict(converged="+", diverged=".")
    return "".join(symbols.get(r["outcome"], "E") for r in sorted(rows, key=lambda r: r[parameter]))


def run_scaling(args):
    scene_path = os.path.join(root, "prm", "patin_elastic.prm")
    table = []
    bugs = []
    for refinements, E, mu in SCALING_CONFIGS:
        h = face_size(refinements)
        settings = [NEWTON_BUDGET, f"Geometry/block/Global refinements={refinements}",
                    f"Material/linear elastic/Young's modulus={E!r}",
                    f"Contact/Friction law/Coulomb/Friction coefficient={mu!r}"]
        for algorithm in ALGORITHMS:
            text = build_scene(scene_path, settings, algorithm, max_cuts=0)
            for parameter, values in (("r_n", SCALING_RN), ("r_t", SCALING_RT)):
                fixed = SCALING_FIXED[parameter]
                name = f"ref{refinements}_E{E:g}_mu{mu:g}_{algorithm}_{parameter}"
                print(f"== scaling: {name}", flush=True)
                case_root = os.path.join(args.workdir, "scaling", name)
                if parameter == "r_n":
                    rows = sweep(args.executable, text, log_grid(*values), [fixed], case_root, args.jobs, args.timeout)
                else:
                    rows = sweep(args.executable, text, [fixed], log_grid(*values), case_root, args.jobs, args.timeout)
                write_csv(rows, os.path.join(case_root, "sweep.csv"))
                grid_values = log_grid(*values)
                for r in rows:
                    index = grid_values.index(r[parameter])
                    case = f"rn{index:02d}_rt00" if parameter == "r_n" else f"rn00_rt{index:02d}"
                    bugs.append((r, os.path.join(case_root, case)))
                best, r_min, r_max = sweep_bounds(rows, parameter)
                scale = E if parameter == "r_n" else mu
                table.append(dict(
                    refinements=refinements, h_mm=h, E_MPa=E, mu=mu, algorithm=algorithm, parameter=parameter,
                    fixed_other=fixed, converged=sum(r["outcome"] == "converged" for r in rows), points=len(rows),
                    best_value=best and best[parameter], best_mean_newton_per_step=best and best["mean_newton_per_step"],
                    r_min=r_min, r_max=r_max, C_min=r_min and r_min * h / scale, C_max=r_max and r_max * h / scale,
                    failures=sum(is_bug(r) for r in rows), pattern=pattern(rows, parameter)))
    with open(os.path.join(results_folder, "robustness_scaling.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(SCALING_COLUMNS)
        for row in table:
            writer.writerow(["" if row[c] is None else (repr(row[c]) if isinstance(row[c], float) else row[c])
                             for c in SCALING_COLUMNS])
    plot_scaling(table, os.path.join(results_folder, "robustness_scaling.png"))
    return scaling_markdown(table), bugs


def plot_scaling(table, png_path):
    """r_max (filled, solid) and r_min (open, dashed) against h, log-log, one panel per parameter; the
    values beyond the swept range are drawn at its end as triangles pointing out of it."""
    figure = Figure(figsize=(13, 5.5), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(1, 2)
    colours = dict(nested="tab:blue", newton="tab:orange")
    series = [((2e5, 0.1), "o", "E = 2e5, μ = 0.1"), ((2e4, 0.1), "s", "E = 2e4, μ = 0.1"),
              ((2e5, 0.3), "D", "E = 2e5, μ = 0.3")]
    for ax, parameter, values in zip(axes, ("r_n", "r_t"), (SCALING_RN, SCALING_RT)):
        low, high = values[0], values[1]
        for algorithm in ALGORITHMS:
            for (E, mu), marker, _ in series:
                rows = sorted((r for r in table if r["parameter"] == parameter and r["algorithm"] == algorithm
                               and r["E_MPa"] == E and r["mu"] == mu), key=lambda r: r["h_mm"])
                # nested a little left of h, Newton a little right, so that equal values stay visible
                shift = 0.95 if algorithm == "nested" else 1.05
                for key, style, beyond, edge_marker in (("r_max", "-", high, "^"), ("r_min", "--", low, "v")):
                    h = [r["h_mm"] * shift for r in rows]
                    v = [r[key] for r in rows]
                    inside = [(x, y) for x, y in zip(h, v) if y is not None]
                    if inside:
                        ax.plot(*zip(*inside), style, marker=marker, color=colours[algorithm], markersize=8,
                                markerfacecolor=colours[algorithm] if key == "r_max" else "white")
                    outside = [x for x, y, r in zip(h, v, rows) if y is None and r["converged"]]
                    if outside:
                        ax.plot(outside, [beyond] * len(outside), edge_marker, color=colours[algorithm],
                                markersize=9, alpha=0.6, linestyle="none")
        # reference slope: proportional to 1/h through the middle h
        h_ref = np.array([face_size(3), face_size(5)])
        for level in np.geomspace(low, high, 5)[1:-1]:
            ax.plot(h_ref, level * face_size(4) / h_ref, ":", color="grey", linewidth=1)
        ax.axhline(low, color="lightgrey", linewidth=0.8)
        ax.axhline(high, color="lightgrey", linewidth=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks([face_size(r) for r in (3, 4, 5)], [f"{face_size(r):g}" for r in (3, 4, 5)])
        ax.set_xticks([], minor=True)
        ax.set_xlim(face_size(5) / 1.3, face_size(3) * 1.3)
        ax.set_ylim(low / 10, high * 10)
        ax.set_xlabel("h (mm)")
        unit = "N/mm$^3$" if parameter == "r_n" else "1/mm"
        other = "r_t = 1" if parameter == "r_n" else "r_n = 1e4"
        ax.set_ylabel(f"${parameter}$ ({unit})")
        ax.set_title(f"elastic patin: ${parameter}$ range against h ({other})")
    handles = [Line2D([], [], color=colours[a], linewidth=2, label=ALGORITHM_NAMES[a]) for a in ALGORITHMS]
    handles += [Line2D([], [], marker=m, color="black", linestyle="none", label=label) for _, m, label in series]
    handles += [Line2D([], [], color="black", linestyle="-", marker="o", label="r_max"),
                Line2D([], [], color="black", linestyle="--", marker="o", markerfacecolor="white", label="r_min"),
                Line2D([], [], color="black", marker="^", alpha=0.6, linestyle="none",
                       label="r_max beyond the range"),
                Line2D([], [], color="black", marker="v", alpha=0.6, linestyle="none",
                       label="r_min beyond the range"),
                Line2D([], [], color="grey", linestyle=":", label="∝ 1/h")]
    axes[-1].legend(handles=handles, loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=9)
    figure.savefig(png_path, dpi=120)


def spread(values):
    """max/min of the positive values, or None with fewer than two."""
    values = [v for v in values if v is not None]
    return max(values) / min(values) if len(values) >= 2 else None


def scaling_markdown(table):
    step = 10 ** 0.5
    lines = [f"Elastic patin (`prm/patin_elastic.prm`), 1D sweeps at 2 points per decade: r_n = "
             f"{fmt(SCALING_RN[0])}..{fmt(SCALING_RN[1])} at r_t = {fmt(SCALING_FIXED['r_n'])}, r_t = "
             f"{fmt(SCALING_RT[0])}..{fmt(SCALING_RT[1])} at r_n = {fmt(SCALING_FIXED['r_t'])}; Maximum step cuts "
             "= 0 and 300 Newton iterations per load step, as for the maps. h = 100 mm / (2·2^refinements). "
             "r_max (r_min) = the largest (smallest) converged value before the first failure above (below) the "
             "value with the fewest iterations (ties: the smallest value); \"none in range\" = converged up to "
             "the end of the range. C = r·h/E for r_n (N/mm³·mm/MPa, dimensionless), C = r·h/μ for r_t "
             "(dimensionless); \"≥ X\" (\"≤ X\"): r_max (r_min) is beyond the range, X is C at its end. The "
             "grid step is a factor √10 ≈ 3.16, so each r_max, r_min and C is known to within that factor only. "
             "Outcomes: one character per swept value, + converged, . diverged, E error/timeout. "
             "Data: `robustness_scaling.csv`, beside this page.", "",
             "![scaling](robustness_scaling.png)", ""]
    for parameter, scale_name, values in (("r_n", "E", SCALING_RN), ("r_t", "μ", SCALING_RT)):
        lines += [f"#### {parameter} (C = {parameter}·h/{scale_name})", "",
                  "| refinements | h (mm) | E (MPa) | μ | algorithm | converged | fewest iterations (at) "
                  f"| {parameter},min | {parameter},max | C_min | C_max | outcomes, {fmt(values[0])} → "
                  f"{fmt(values[1])} |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in (r for r in table if r["parameter"] == parameter):
            def bound(value):
                if not r["converged"]:
                    return "none converged"
                return "none in range" if value is None else fmt(value, 2)

            def constant(value, end, relation):
                """C, or the bound on it given by the end of the range when r is beyond it."""
                if value is not None or not r["converged"]:
                    return fmt(value)
                return f"{relation} {fmt(end * r['h_mm'] / (r['E_MPa'] if parameter == 'r_n' else r['mu']))}"

            lines.append(
                f"| {r['refinements']} | {r['h_mm']:g} | {r['E_MPa']:g} | {r['mu']:g} | {r['algorithm']} "
                f"| {r['converged']}/{r['points']} | {fmt(r['best_mean_newton_per_step'])} "
                f"({fmt(r['best_value'], 2)}) "
                f"| {bound(r['r_min'])} | {bound(r['r_max'])} "
                f"| {constant(r['C_min'], values[0], '≤')} | {constant(r['C_max'], values[1], '≥')} "
                f"| `{r['pattern']}` |")
        lines.append("")
    # the checks of proportionality: the spread of C over the configurations, and the ratios of r_max
    lines += ["#### Proportionality checks", "",
              f"Spread = max/min of C over the configurations where it is in range (1 = constant; up to "
              f"{step:.2f} = one grid step is within the resolution). Expected ratios if r ∝ E/h, μ/h: "
              "refinement 3→4→5 halves h, so r_max doubles per refinement (×4 from 3 to 5); E 2e4→2e5 is ×10 "
              "on r_n; μ 0.1→0.3 is ×3 on r_t (one grid step: barely resolved).", "",
              "| parameter | algorithm | bound | spread of C | r(ref 5)/r(ref 3) (expect 4 for ∝1/h) "
              "| r(E=2e5)/r(E=2e4) | r(μ=0.3)/r(μ=0.1) |",
              "|---|---|---|---|---|---|---|"]

    def value(parameter, algorithm, key, refinements, E, mu):
        for r in table:
            if (r["parameter"], r["algorithm"], r["refinements"], r["E_MPa"], r["mu"]) == (
                    parameter, algorithm, refinements, E, mu):
                return r[key]
        return None

    def ratio(a, b):
        return "–" if a is None or b is None else f"{a / b:.3g}"

    for parameter in ("r_n", "r_t"):
        for algorithm in ALGORITHMS:
            for key, c_key in (("r_max", "C_max"), ("r_min", "C_min")):
                c_spread = spread([r[c_key] for r in table if r["parameter"] == parameter
                                   and r["algorithm"] == algorithm])
                lines.append(
                    f"| {parameter} | {algorithm} | {key} | {fmt(c_spread)} "
                    f"| {ratio(value(parameter, algorithm, key, 5, 2e5, 0.1), value(parameter, algorithm, key, 3, 2e5, 0.1))} "
                    f"| {ratio(value(parameter, algorithm, key, 4, 2e5, 0.1), value(parameter, algorithm, key, 4, 2e4, 0.1))} "
                    f"| {ratio(value(parameter, algorithm, key, 4, 2e5, 0.3), value(parameter, algorithm, key, 4, 2e5, 0.1))} |")
    lines.append("")
    return lines


# ----------------------------------------------------------------------------------------- automatic

def automatic_scene(scene_path, algorithm, factor):
    """The scene with r_n = r_t = automatic times factor and the loops of algorithm; the step cuts and the
    Newton budget as shipped (not appended)."""
    with open(scene_path) as f:
        text = f.read()
    if algorithm == "newton":
        text += robustness_map.GENERALIZED_NEWTON
    for entry, value in (("r_n", "automatic"), ("r_t", "automatic"), ("Automatic r_n factor", repr(factor)),
                         ("Automatic r_t factor", repr(factor))):
        text += nested_set(f"Contact/{entry}", value)
    return text + robustness_map.OUTPUT_SECTION


def used_parameters(case_dir):
    """r_n and r_t the run printed ('r_n = automatic: ... = VALUE ...'), None if not printed."""
    values = dict(r_n=None, r_t=None)
    try:
        with open(os.path.join(case_dir, "log.txt")) as f:
            for line in f:
                match = re.match(r"\s*(r_[nt]) = automatic: \S+ x \S+ ?(?:E/h|/l) = (\S+) ", line)
                if match:
                    values[match.group(1)] = float(match.group(2))
    except FileNotFoundError:
        pass
    return values


def run_cases(executable, cases, jobs, timeout):
    """cases: list of (key, text, case_dir); robustness_map.run_cases with the r_n, r_t each case
    printed (run_summary.csv has them only when it converged); {key: row}."""
    case_dirs = {key: case_dir for key, _, case_dir in cases}

    def with_parameters(key, row):
        row.update(used_parameters(case_dirs[key]))
        return f"{key}: {robustness_map.describe(row)}"

    return robustness_map.run_cases(executable, cases, jobs, timeout, with_parameters)


def run_automatic(args):
    cases = []
    for scene, _ in AUTOMATIC_SCENES:
        for algorithm in ALGORITHMS:
            for factor in AUTOMATIC_FACTORS:
                case_dir = os.path.join(args.workdir, "automatic", scene, algorithm, f"f{factor:g}")
                cases.append(((scene, algorithm, factor),
                              automatic_scene(os.path.join(root, "prm", f"{scene}.prm"), algorithm, factor), case_dir))
    results = run_cases(args.executable, cases, args.jobs, args.timeout)
    table = []
    for (scene, algorithm, factor), _, case_dir in cases:
        row = results[scene, algorithm, factor]
        table.append(dict(scene=scene, algorithm=algorithm, factor=factor, case_dir=case_dir, **row))
    with open(os.path.join(results_folder, "robustness_automatic.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(AUTOMATIC_COLUMNS)
        for row in table:
            writer.writerow(["" if row[c] is None else str(row[c]).lower() if isinstance(row[c], bool)
                             else repr(row[c]) if isinstance(row[c], float) else row[c] for c in AUTOMATIC_COLUMNS])
    return automatic_markdown(table), [(r, r["case_dir"]) for r in table]


def automatic_markdown(table):
    def cell(r, key):
        if r["outcome"] != "converged":
            return r["outcome"] if r["outcome"] != "diverged" else "div."
        return fmt(r[key])

    header = "| scene | algorithm | " + " | ".join(f"f = {f:g}" for f in AUTOMATIC_FACTORS) + " |"
    rule = "|---|---|" + "---|" * len(AUTOMATIC_FACTORS)
    lines = ["r_n = r_t = automatic (r_n = f·C_n·E/h, r_t = f·C_t/l with l the largest prescribed displacement "
             "increment of a load step; C_n and C_t in include/stabilized_lagrangian/contact/stabilized_lagrangian.h; "
             "the Hertz cylinder is frictionless, r_t scales no rows there) with both Automatic factors = f; the step "
             "cuts (5) and the Newton budget (2000 per load step) as shipped, so \"div.\" = still failing at the "
             "smallest cut step. Data: `robustness_automatic.csv`, beside this page.", "",
             "Values at f = 1:", "",
             "| scene | r_n (N/mm³) | r_t (1/mm) |", "|---|---|---|"]
    for scene, title in AUTOMATIC_SCENES:
        r = next(r for r in table if r["scene"] == scene and r["factor"] == 1.0)
        lines.append(f"| {title} | {fmt(r['r_n'], 4)} | {fmt(r['r_t'], 4)} |")
    for key, caption in (("mean_newton_per_step", "Mean Newton iterations per load step (all loops)"),
                         ("load_steps", "Load steps done (10 as shipped, 2 on the Hertz cylinder; more = cut steps)"),
                         ("wall_time_s", "Wall time (s) of the run, diverged ones included")):
        lines += ["", f"{caption}:", "", header, rule]
        for scene, title in AUTOMATIC_SCENES:
            for algorithm in ALGORITHMS:
                rows = {r["factor"]: r for r in table if r["scene"] == scene and r["algorithm"] == algorithm}
                if key == "wall_time_s":
                    cells = [fmt(rows[f]["wall_time_s"], 2) for f in AUTOMATIC_FACTORS]
                else:
                    cells = [cell(rows[f], key) for f in AUTOMATIC_FACTORS]
                lines.append(f"| {title} | {algorithm} | " + " | ".join(cells) + " |")
    lines += ["", "Worst/best over f ∈ [1e-4, 1e4] (mean iterations, and wall time):", "",
              "| scene | algorithm | best mean (f) | worst mean (f) | ratio | wall-time ratio |",
              "|---|---|---|---|---|---|"]
    for scene, title in AUTOMATIC_SCENES:
        for algorithm in ALGORITHMS:
            rows = [r for r in table if r["scene"] == scene and r["algorithm"] == algorithm
                    and 1e-4 <= r["factor"] <= 1e4]
            failed = [r for r in rows if r["outcome"] != "converged"]
            converged = [r for r in rows if r["outcome"] == "converged"]
            times = [r["wall_time_s"] for r in rows]
            time_ratio = f"{max(times) / min(times):.3g}"
            if not converged:
                lines.append(f"| {title} | {algorithm} | – | – | none converged | {time_ratio} |")
                continue
            best = min(converged, key=lambda r: r["mean_newton_per_step"])
            worst = max(converged, key=lambda r: r["mean_newton_per_step"])
            ratio = f"{worst['mean_newton_per_step'] / best['mean_newton_per_step']:.3g}"
            if failed:
                ratio = "∞ (failed at f = " + ", ".join(f"{r['factor']:g}" for r in failed) + f"; {ratio} over the converged)"
            lines.append(f"| {title} | {algorithm} | {fmt(best['mean_newton_per_step'])} ({best['factor']:g}) "
                         f"| {fmt(worst['mean_newton_per_step'])} ({worst['factor']:g}) | {ratio} | {time_ratio} |")
    lines.append("")
    return lines


# ---------------------------------------------------------------------------------------- markdown

def write_results(part, body, command, seconds, bugs):
    """Replace the section of part in robustness_results.md (the other parts' sections are kept)."""
    titles = dict(maps="A. Robustness maps r_n × r_t", scaling="B. Scaling of the convergence bounds with E, μ, h",
                  automatic="C. Automatic parameters scaled by a factor")
    sections = {}
    if os.path.exists(results_md):
        with open(results_md) as f:
            text = f.read()
        for name in PARTS:
            match = re.search(rf"<!-- begin {name} -->\n.*?<!-- end {name} -->\n", text, re.S)
            if match:
                sections[name] = match.group(0)
    bug_list = bug_lines(bugs)
    lines = [f"<!-- begin {part} -->", f"## {titles[part]}", "",
             f"Generated by `{command}` on {time.strftime('%Y-%m-%d %H:%M')}; the part took "
             f"{seconds / 60:.1f} min ({seconds:.0f} s) of wall time.", ""]
    lines += body
    lines += ["Cases ended in error, timeout or with a NaN/inf in their output (program bugs):", ""]
    lines += bug_list or ["none.", ""]
    if bug_list:
        lines.append("")
    lines.append(f"<!-- end {part} -->")
    sections[part] = "\n".join(lines) + "\n"
    header = ["# Robustness study of the augmentation parameters r_n, r_t", "",
              "Generated file, do not edit: written by `contrib/robustness_study.py"
              + (" --doc" if results_folder == tool_cli.DOC else "") + "` (each section below says "
              "the command that produced it; `--part all` writes them all). The per-case input.prm and log.txt are "
              "in the --workdir (default /tmp/robustness_study).", ""]
    with open(results_md, "w") as f:
        f.write("\n".join(header) + "\n" + "\n".join(sections[name] for name in PARTS if name in sections))
    print(f"wrote section '{part}' of {results_md}")
    return len(bug_list)


def main():
    global results_folder, results_md
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--executable", required=True, type=tool_cli.executable)
    parser.add_argument("--workdir", default="/tmp/robustness_study", help="where the cases run (default: %(default)s)")
    parser.add_argument("--part", choices=PARTS + ["all"], default="all")
    parser.add_argument("--jobs", type=tool_cli.positive_int, default=os.cpu_count())
    parser.add_argument("--timeout", type=tool_cli.positive_float, default=600, help="seconds per case (default 600)")
    tool_cli.add_output_arguments(parser, None, ["robustness_results.md", "its CSV files and plots"])
    args = parser.parse_args()
    args.workdir = os.path.abspath(args.workdir)
    args.output = args.output or args.workdir
    tool_cli.check_output(parser, args)
    results_md = tool_cli.destination(args, "robustness_results.md")
    results_folder = os.path.dirname(results_md)
    command = " ".join(["contrib/robustness_study.py"] + [shlex.quote(a) for a in sys.argv[1:]])
    runners = dict(maps=run_maps, scaling=run_scaling, automatic=run_automatic)
    bug_count = 0
    for part in PARTS if args.part == "all" else [args.part]:
        start = time.monotonic()
        body, bugs = runners[part](args)
        seconds = time.monotonic() - start
        bug_count += write_results(part, body, command, seconds, bugs)
        print(f"part {part}: {seconds:.0f} s", flush=True)
    if bug_count:
        print(f"{bug_count} case(s) ended in error, timeout or NaN: see {results_md}")
    return 1 if bug_count else 0


if __name__ == "__main__":
    sys.exit(main())
