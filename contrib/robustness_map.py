#!/usr/bin/python3
"""Robustness map over the augmentation parameters r_n x r_t (the seed paper's Fig. 3).

Usage: contrib/robustness_map.py --executable build/stabilized_lagrangian --scene prm/patin_elastic.prm
           [--label TEXT] [--rn MIN MAX N] [--rt MIN MAX N] [--set 'Section/Sub/Entry=value' ...]
           [--algorithm nested|newton] [--max-cuts N] [--jobs N] [--timeout SECONDS]
           [--workdir DIR] [--output FOLDER] [--name NAME]

Runs the scene for every (r_n, r_t) of a log-spaced grid (N values from MIN to
MAX each), in parallel, each case in its own directory WORKDIR/rnII_rtJJ, and
writes FOLDER/NAME.csv (one row per case) and FOLDER/NAME.png (a heat map of the mean
Newton iterations per load step; diverged cells grey with an x, error/timeout
cells red, the edge of the converged region in black). With the default
--max-cuts 0 a load step that fails is not retried with a smaller step, so a
failure means divergence, as in the paper.

The scene is the parameter file with, appended in this order (later sets win):
the Maximum step cuts, the loop methods of --algorithm newton, the --set
entries, then per case r_n, r_t and the output settings.

Outcome of a case: converged (exit 0), diverged (exit 2), error (any other exit
code, negative = killed by that signal, or exit 0 without run_summary.csv) or
timeout (process group killed after --timeout s). nan_in_output is true if a
CSV file the run wrote holds a NaN or infinite value. The tool exits with 1 if
any case ended in error or timeout or wrote a NaN: those are bugs, a divergence
is not. At the end it prints the converged r_n range per r_t, the converged r_t
range per r_n and the largest all-converged rectangle I1 x I2 of the grid.

The functions (read_scene, build_scene, run_cases, sweep, write_csv, read_csv,
draw_map, plot_map, convergence_bounds) can be imported by a study script or
another tool (contrib/compare.py runs its cases with run_cases): draw_map
draws on a given axes, e.g. to put the nested and the Newton maps side by side."""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.colors import ListedColormap, Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402

COLUMNS = ["r_n", "r_t", "outcome", "exit_code", "load_steps", "newton_iterations", "mean_newton_per_step",
           "wall_time_s", "nan_in_output"]
OUTCOMES = ["converged", "diverged", "error", "timeout"]
OUTPUT_SECTION = "\nsubsection Output\n  set Output directory = output\n  set Write vtu = false\nend\n"


def write_section(path, begin, end, block):
    """Replace the part of the Markdown file `path` between the markers `begin` and `end`
    (included) by `block`, which starts with `begin` and ends with `end`; append it when the
    file has no such part, so that several scripts can write one file."""
    text = ""
    if os.path.exists(path):
        with open(path) as f:
            text = f.read()
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if pattern.search(text):
        text = pattern.sub(lambda _: block, text)
    else:
        text = text.rstrip("\n") + ("\n\n" if text else "") + block
    with open(path, "w") as f:
        f.write(text)


def nested_set(path, value):
    """'Section/Sub/Entry', value -> the parameter file text setting it in nested subsections."""
    *sections, entry = path.split("/")
    lines = [f"{'  ' * depth}subsection {name}" for depth, name in enumerate(sections)]
    lines.append(f"{'  ' * len(sections)}set {entry} = {value}")
    lines += [f"{'  ' * depth}end" for depth in reversed(range(len(sections)))]
    return "\n" + "\n".join(lines) + "\n"


# the geometry, friction and status loops all folded into the generalized Newton
GENERALIZED_NEWTON = "".join(nested_set(f"Nonlinear solver/{loop}/Method", "newton")
                             for loop in ("Geometry loop", "Friction loop", "Status loop"))


INCLUDE = re.compile(r"^\s*(?:include|INCLUDE)(?:\s+([^#]*?))?\s*(?:#.*)?$")
MESH_FILE = re.compile(r"^(\s*set\s+Mesh file\s*=\s*)([^#]*?)(\s*(?:#.*)?)$")


def read_scene(scene_path, _including=()):
    """The text of the parameter file scene_path as a run in another directory needs it: each
    `include` line replaced by the included file's text (looked up as the program does, as given,
    then beside the including file) and a relative `Mesh file` made absolute (as given, then
    beside scene_path). ValueError for a file that cannot be read or includes itself."""
    if len(_including) > 20:
        raise ValueError(f"more than 20 nested include statements at '{scene_path}'")
    try:
        with open(scene_path) as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as error:
        raise ValueError(f"cannot read the parameter file '{scene_path}': {error}") from None
    directory = os.path.dirname(os.path.abspath(scene_path))
    top = os.path.dirname(os.path.abspath(_including[0])) if _including else directory
    text = []
    for line in lines:
        include = INCLUDE.match(line)
        mesh = MESH_FILE.match(line)
        if include and include.group(1):
            name = include.group(1)
            if not os.path.isabs(name) and not os.path.exists(name):
                name = os.path.join(directory, name)
            text.append(read_scene(name, _including + (scene_path,)).rstrip("\n"))
        elif mesh and mesh.group(2) and not os.path.isabs(mesh.group(2)):
            name = mesh.group(2)
            name = os.path.abspath(name if os.path.exists(name) else os.path.join(top, name))
            text.append(mesh.group(1) + name + mesh.group(3))
        else:
            text.append(line)
    return "\n".join(text) + "\n"


def build_scene(scene_path, settings=(), algorithm="nested", max_cuts=0):
    """The scene's parameter text (read_scene) with the step cuts, the algorithm and the
    'Section/Entry=value' settings."""
    text = read_scene(scene_path)
    text += nested_set("Load stepping/Maximum step cuts", max_cuts)
    if algorithm == "newton":
        text += GENERALIZED_NEWTON
    elif algorithm != "nested":
        raise ValueError(f"unknown algorithm '{algorithm}' (nested or newton)")
    for setting in settings:
        path, sep, value = setting.partition("=")
        if not sep:
            raise ValueError(f"setting '{setting}' is not of the form Section/Entry=value")
        text += nested_set(path.strip(), value.strip())
    return text


def log_grid(low, high, n):
    """n log-spaced values from low to high."""
    return [float(v) for v in np.geomspace(low, high, n)]


def has_nan(directory):
    """Whether a CSV file under directory holds a cell that parses as a NaN or an infinity."""
    for parent, _, files in os.walk(directory):
        for name in files:
            if name.endswith(".csv"):
                with open(os.path.join(parent, name), newline="") as f:
                    for row in csv.reader(f):
                        for cell in row:
                            try:
                                if not math.isfinite(float(cell)):
                                    return True
                            except ValueError:  # text cell
                                pass
    return False


class Running:
    """The process groups of the cases being run, to kill them if the sweep is interrupted."""

    def __init__(self):
        self.lock = threading.Lock()
        self.processes = set()
        self.stopped = False

    def start(self, command, cwd, log, env):
        with self.lock:
            if self.stopped:
                return None
            # its own session, hence process group: a timeout kills the program and all its children
            process = subprocess.Popen(command, cwd=cwd, stdout=log, stderr=subprocess.STDOUT, env=env,
                                       start_new_session=True)
            self.processes.add(process)
            return process

    def finish(self, process):
        with self.lock:
            self.processes.discard(process)

    def kill_all(self):
        with self.lock:
            self.stopped = True
            for process in self.processes:
                kill_group(process)


def kill_group(process):
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:  # already gone
        pass


def run_case(executable, text, case_dir, timeout, running, ranks=1):
    """Run one case in case_dir (emptied first), on `ranks` MPI ranks, and return its row without
    r_n, r_t."""
    shutil.rmtree(case_dir, ignore_errors=True)
    os.makedirs(case_dir)
    with open(os.path.join(case_dir, "input.prm"), "w") as f:
        f.write(text)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    command = [executable, "input.prm"]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
    row = dict(outcome="error", exit_code=None, load_steps=None, newton_iterations=None,
               mean_newton_per_step=None)
    start = time.monotonic()
    with open(os.path.join(case_dir, "log.txt"), "w") as log:
        process = running.start(command, case_dir, log, env)
        if process is None:  # the sweep was interrupted
            return None
        try:
            row["exit_code"] = process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            kill_group(process)
            process.wait()
            row["outcome"] = "timeout"
        finally:
            running.finish(process)
    row["wall_time_s"] = round(time.monotonic() - start, 3)
    summary_path = os.path.join(case_dir, "output", "run_summary.csv")
    if row["exit_code"] == 0 and os.path.exists(summary_path):
        with open(summary_path) as f:
            summary = next(csv.DictReader(f))
        row.update(outcome="converged", load_steps=int(summary["load_steps"]),
                   newton_iterations=int(summary["newton_iterations"]),
                   mean_newton_per_step=float(summary["mean_newton_iterations_per_step"]))
    elif row["exit_code"] == 2:
        row["outcome"] = "diverged"
    row["nan_in_output"] = has_nan(case_dir)
    return row


def describe(row):
    text = f"r_n = {row['r_n']:.4g}, r_t = {row['r_t']:.4g}: {row['outcome']}"
    if row["outcome"] == "converged":
        text += f", {row['mean_newton_per_step']:.2f} Newton iterations per step"
    elif row["outcome"] == "error":
        text += f" (exit code {row['exit_code']})"
    if row["nan_in_output"]:
        text += ", NaN in output"
    return text + f", {row['wall_time_s']:.1f} s"


def run_cases(executable, cases, jobs=None, timeout=600, label=lambda key, row: describe(row)):
    """cases: list of (key, text, case_dir); run them jobs at a time with run_case, printing
    label(key, row) as each ends; {key: row}. A case running longer than timeout seconds is
    killed with its process group, and so are the running ones if the caller is interrupted."""
    executable = os.path.abspath(executable)
    running = Running()
    rows = {}
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs or os.cpu_count())
    try:
        futures = {pool.submit(run_case, executable, text, case_dir, timeout, running): key
                   for key, text, case_dir in cases}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            key = futures[future]
            rows[key] = future.result()
            print(f"[{done}/{len(cases)}] {label(key, rows[key])}", flush=True)
    except BaseException:  # e.g. Ctrl-C: the cases run in their own sessions, so kill them here
        pool.shutdown(wait=False, cancel_futures=True)
        running.kill_all()
        raise
    pool.shutdown()
    return rows


def sweep(executable, scene_text, rn_values, rt_values, workdir, jobs=None, timeout=600):
    """Run scene_text for every r_n x r_t, jobs at a time, in workdir/rnII_rtJJ; the rows, r_t-major order.

    Contact/r_n, Contact/r_t and the output settings are appended to scene_text;
    a case running longer than timeout seconds is killed with its process group."""
    grid = [(i, j, rn, rt) for j, rt in enumerate(rt_values) for i, rn in enumerate(rn_values)]
    # repr: the value run is the value recorded
    cases = [((rn, rt), scene_text + nested_set("Contact/r_n", repr(rn)) + nested_set("Contact/r_t", repr(rt))
              + OUTPUT_SECTION, os.path.join(workdir, f"rn{i:02d}_rt{j:02d}")) for i, j, rn, rt in grid]

    def with_parameters(key, row):
        row.update(r_n=key[0], r_t=key[1])
        return describe(row)

    rows = run_cases(executable, cases, jobs, timeout, with_parameters)
    return [rows[rn, rt] for _, _, rn, rt in grid]


def write_csv(rows, path, columns=COLUMNS):
    """rows (dicts) as CSV with the given columns; None, or a column a row lacks, is an empty cell."""
    def text(value):
        if value is None:
            return ""
        if isinstance(value, bool):
            return str(value).lower()
        return repr(value) if isinstance(value, float) else str(value)

    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([text(row.get(c)) for c in columns])


def read_csv(path):
    """The rows written by write_csv, with their types (None for an empty cell)."""
    types = dict(r_n=float, r_t=float, outcome=str, exit_code=int, load_steps=int, newton_iterations=int,
                 mean_newton_per_step=float, wall_time_s=float, nan_in_output=lambda v: v == "true")
    with open(path, newline="") as f:
        return [{k: types[k](v) if v != "" else None for k, v in row.items()} for row in csv.DictReader(f)]


def grid(rows):
    """The sorted r_n and r_t values and the row of each cell, cells[j][i] for r_t[j], r_n[i] (None if missing)."""
    rn_values = sorted({r["r_n"] for r in rows})
    rt_values = sorted({r["r_t"] for r in rows})
    by_value = {(r["r_n"], r["r_t"]): r for r in rows}
    return rn_values, rt_values, [[by_value.get((rn, rt)) for rn in rn_values] for rt in rt_values]


def cell_edges(values):
    """Cell edges around log-spaced values: geometric midpoints, half a spacing (or a decade) outside."""
    logs = np.log10(values)
    half = np.diff(logs) / 2 if len(logs) > 1 else np.array([0.5])
    return 10 ** np.concatenate([[logs[0] - half[0]], logs[:-1] + half, [logs[-1] + half[-1]]])


def converged_mask(cells):
    return np.array([[c is not None and c["outcome"] == "converged" for c in line] for line in cells])


def draw_map(ax, rows, title, norm=None):
    """Draw the map of rows on ax; returns the mappable of the iteration colours (for a colorbar).

    norm (a matplotlib Normalize) sets the colour scale, e.g. the same for maps side by side;
    by default it spans the converged cells' mean iterations, rounded out to whole iterations."""
    rn_values, rt_values, cells = grid(rows)
    x_edges, y_edges = cell_edges(rn_values), cell_edges(rt_values)
    converged = converged_mask(cells)
    mean = np.ma.masked_array([[c["mean_newton_per_step"] if c is not None and c["outcome"] == "converged"
                                else np.nan for c in line] for line in cells], mask=~converged)
    if norm is None:  # whole iterations, at least one apart: close counts are not blown up into the whole scale
        low, high = (math.floor(mean.min()), math.ceil(mean.max())) if converged.any() else (0, 1)
        norm = Normalize(low, max(high, low + 1))
    mappable = ax.pcolormesh(x_edges, y_edges, mean, cmap="viridis", norm=norm)
    # the failed cells: 0 = diverged (grey), 1 = error or timeout (red)
    failed = np.ma.masked_array([[1 if c is not None and c["outcome"] in ("error", "timeout") else 0
                                  for c in line] for line in cells],
                                mask=[[c is None or c["outcome"] == "converged" for c in line] for line in cells])
    ax.pcolormesh(x_edges, y_edges, failed, cmap=ListedColormap(["lightgrey", "red"]), vmin=0, vmax=1)
    diverged = [(c["r_n"], c["r_t"]) for line in cells for c in line if c is not None and c["outcome"] == "diverged"]
    if diverged:
        ax.plot(*zip(*diverged), "x", color="dimgrey", markersize=8)
    # the converged region's boundary: every edge between a converged and a non-converged cell
    segments = []
    for j in range(len(rt_values)):
        for i in range(len(rn_values)):
            if i + 1 < len(rn_values) and converged[j, i] != converged[j, i + 1]:
                segments.append([(x_edges[i + 1], y_edges[j]), (x_edges[i + 1], y_edges[j + 1])])
            if j + 1 < len(rt_values) and converged[j, i] != converged[j + 1, i]:
                segments.append([(x_edges[i], y_edges[j + 1]), (x_edges[i + 1], y_edges[j + 1])])
    ax.add_collection(LineCollection(segments, colors="black", linewidths=2.5, capstyle="projecting"))
    if len(rn_values) <= 15 and len(rt_values) <= 15:
        for line in cells:
            for c in line:
                if c is not None and c["outcome"] == "converged":
                    red, green, blue, _ = mappable.cmap(norm(c["mean_newton_per_step"]))
                    dark = 0.299 * red + 0.587 * green + 0.114 * blue < 0.5
                    ax.text(c["r_n"], c["r_t"], f"{c['mean_newton_per_step']:.1f}", ha="center", va="center",
                            fontsize=7, color="white" if dark else "black")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(x_edges[0], x_edges[-1])
    ax.set_ylim(y_edges[0], y_edges[-1])
    ax.set_xlabel(r"$r_n$ (N/mm$^3$)")
    ax.set_ylabel(r"$r_t$ (1/mm)")
    ax.set_title(title)
    outcomes = {c["outcome"] for line in cells for c in line if c is not None}
    legend = []
    if "diverged" in outcomes:
        # a tuple of handles is drawn overlaid: the x on the grey cell
        legend.append(((Patch(color="lightgrey"), Line2D([], [], color="dimgrey", marker="x", linestyle="none")),
                       "diverged"))
    if outcomes & {"error", "timeout"}:
        legend.append((Patch(color="red"), "error / timeout"))
    if legend:
        ax.legend(*zip(*legend), loc="upper left", bbox_to_anchor=(0, -0.12), ncol=2, fontsize=8, frameon=False)
    return mappable


def plot_map(rows, title, png_path):
    """The map of rows, with a colorbar, as a PNG."""
    figure = Figure(figsize=(7, 5.5), layout="constrained")
    FigureCanvasAgg(figure)
    ax = figure.add_subplot()
    figure.colorbar(draw_map(ax, rows, title), ax=ax, label="mean Newton iterations per load step")
    figure.savefig(png_path, dpi=150)


def largest_rectangle(ok):
    """The largest (most cells) all-True block of the 2D bool array ok: ((i_lo, i_hi), (j_lo, j_hi)) on the
    columns and rows, inclusive, or None. Exhaustive over all blocks with a summed-area table: grids are small."""
    n_rows, n_cols = ok.shape
    table = np.zeros((n_rows + 1, n_cols + 1), dtype=int)
    table[1:, 1:] = ok.cumsum(0).cumsum(1)
    best, best_cells = None, 0
    for j_lo in range(n_rows):
        for j_hi in range(j_lo, n_rows):
            for i_lo in range(n_cols):
                for i_hi in range(i_lo, n_cols):
                    cells = (j_hi - j_lo + 1) * (i_hi - i_lo + 1)
                    count = (table[j_hi + 1, i_hi + 1] - table[j_lo, i_hi + 1] - table[j_hi + 1, i_lo]
                             + table[j_lo, i_lo])
                    if count < cells:  # a failed cell: so are the wider blocks
                        break
                    if cells > best_cells:
                        best, best_cells = ((i_lo, i_hi), (j_lo, j_hi)), cells
    return best


def convergence_bounds(rows):
    """(rn_range, rt_range, rectangle):
    rn_range[r_t] = (min, max) converged r_n at that r_t, or None if none converged (values in between may fail);
    rt_range[r_n] = (min, max) converged r_t at that r_n, or None;
    rectangle = ((rn_lo, rn_hi), (rt_lo, rt_hi)), the largest (most cells) I1 x I2 of the grid, I1 a contiguous
    range of r_n values and I2 one of r_t values, whose cells all converged, or None."""
    rn_values, rt_values, cells = grid(rows)
    ok = converged_mask(cells)

    def value_range(values, flags):
        chosen = [v for v, flag in zip(values, flags) if flag]
        return (chosen[0], chosen[-1]) if chosen else None

    rn_range = {rt: value_range(rn_values, ok[j, :]) for j, rt in enumerate(rt_values)}
    rt_range = {rn: value_range(rt_values, ok[:, i]) for i, rn in enumerate(rn_values)}
    block = largest_rectangle(ok)
    rectangle = None
    if block is not None:
        (i_lo, i_hi), (j_lo, j_hi) = block
        rectangle = ((rn_values[i_lo], rn_values[i_hi]), (rt_values[j_lo], rt_values[j_hi]))
    return rn_range, rt_range, rectangle


def print_bounds(rows):
    rn_range, rt_range, rectangle = convergence_bounds(rows)

    def interval(name, bounds):
        return "none converged" if bounds is None else f"{name} in [{bounds[0]:.4g}, {bounds[1]:.4g}]"

    print("converged r_n per r_t:")
    for rt, bounds in rn_range.items():
        print(f"  r_t = {rt:.4g}: {interval('r_n', bounds)}")
    print("converged r_t per r_n:")
    for rn, bounds in rt_range.items():
        print(f"  r_n = {rn:.4g}: {interval('r_t', bounds)}")
    if rectangle is None:
        print("I1 x I2: none (no case converged)")
    else:
        print(f"I1 x I2 = {interval('r_n', rectangle[0])} x {interval('r_t', rectangle[1])}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--executable", required=True, type=tool_cli.executable)
    parser.add_argument("--scene", required=True, type=tool_cli.existing_file, help="the parameter file")
    parser.add_argument("--label", help="the map's title (default: scene name and algorithm)")
    parser.add_argument("--rn", nargs=3, type=float, metavar=("MIN", "MAX", "N"), default=[1e2, 1e10, 9])
    parser.add_argument("--rt", nargs=3, type=float, metavar=("MIN", "MAX", "N"), default=[1e-4, 1e4, 9])
    parser.add_argument("--set", action="append", default=[], metavar="'Section/Sub/Entry=value'",
                        type=tool_cli.setting, help="an entry to set, repeatable")
    parser.add_argument("--algorithm", choices=["nested", "newton"], default="nested")
    parser.add_argument("--max-cuts", type=int, default=0, help="Load stepping/Maximum step cuts (default 0)")
    parser.add_argument("--jobs", type=tool_cli.positive_int, default=os.cpu_count())
    parser.add_argument("--timeout", type=tool_cli.positive_float, default=600, help="seconds per case (default 600)")
    parser.add_argument("--workdir", help="default /tmp/robustness/<label>")
    parser.add_argument("--output", metavar="FOLDER", help="folder of NAME.csv and NAME.png, created if needed "
                        "(default: WORKDIR)")
    parser.add_argument("--name", default="map", help="name of the CSV and PNG files (default: %(default)s)")
    args = parser.parse_args()
    if args.max_cuts < 0:
        parser.error(f"argument --max-cuts: {args.max_cuts} is not >= 0")
    if "/" in args.name or not args.name:
        parser.error(f"argument --name: '{args.name}' is not a file name")
    for name in ("rn", "rt"):
        low, high, n = getattr(args, name)
        if not (0 < low <= high and n >= 1 and n == int(n)):
            parser.error(f"--{name} MIN MAX N needs 0 < MIN <= MAX and an integer N >= 1")
    label = args.label or f"{os.path.splitext(os.path.basename(args.scene))[0]}, {args.algorithm}"
    workdir = args.workdir or os.path.join("/tmp/robustness", re.sub(r"[^\w.-]+", "_", label).strip("_"))
    folder = args.output or workdir
    if os.path.exists(folder) and not os.path.isdir(folder):
        parser.error(f"argument --output: '{folder}' exists and is not a directory")
    output = os.path.join(folder, args.name)
    try:
        scene_text = build_scene(args.scene, args.set, args.algorithm, args.max_cuts)
    except ValueError as error:
        parser.error(str(error))
    os.makedirs(folder, exist_ok=True)

    rows = sweep(args.executable, scene_text, log_grid(args.rn[0], args.rn[1], int(args.rn[2])),
                 log_grid(args.rt[0], args.rt[1], int(args.rt[2])), workdir, args.jobs, args.timeout)
    write_csv(rows, output + ".csv")
    plot_map(rows, label, output + ".png")
    print(f"wrote {output}.csv and {output}.png; the cases are in {workdir}")
    counts = {outcome: sum(r["outcome"] == outcome for r in rows) for outcome in OUTCOMES}
    with_nan = sum(r["nan_in_output"] for r in rows)
    print(", ".join(f"{counts[o]} {o}" for o in OUTCOMES) + f"; {with_nan} with NaN/inf in their output")
    print_bounds(rows)
    return 1 if counts["error"] or counts["timeout"] or with_nan else 0


if __name__ == "__main__":
    sys.exit(main())
