#!/usr/bin/python3
"""Compare finite element pairs, algorithms, meshes and r factors on a scene: cost against accuracy.

Usage: contrib/compare.py SCENE.prm [--executable build/stabilized_lagrangian]
           [--pairs PAIR ...] [--algorithms nested|newton|scene ...] [--refinements N ...]
           [--rn-factors F ...] [--rt-factors F ...] [--stoppings fixed|adaptive ...]
           [--cell-shapes hypercube|simplex ...]
           [--choice 'pair=Q2/P1, algorithm=newton, refinement=1, rn_factor=1, rt_factor=1, stopping=fixed,
                      cell_shape=hypercube' ['pair=Q1/P1, refinement=2' ...] ...]
           [--set 'Section/Sub/Entry=value' ...] [--measure pressure|normal_force|tangential_force|half_width|peak]
           [--target ERROR] [--reference-pair PAIR] [--reference-refinement N]
           [--against closed-form|reference] [--hertz 'R=..., bodies=1|2']
           [--jobs N] [--timeout SECONDS] [--workdir DIR] [--name NAME] [--output FOLDER | --doc]

Runs the scene once per choice, --jobs runs at a time (contrib/robustness_map.py's
runner: each run in its own directory WORKDIR/NN_..., killed with its process
group after --timeout seconds), and writes into the --output folder (default:
the work directory, /tmp/compare/<scene> unless --workdir; doc/ with --doc):

  NAME.csv   one row per choice: pair, algorithm, refinement, r factors, outcome,
             DoFs, Newton iterations, wall time, peak memory, the errors
             measured, the run's own error estimate, the target marks
  NAME.md    the same as a table, with what the errors are measured against
             and the command that regenerates the page (between two marker
             comments: text after them, notes on the results, is kept when
             the tool writes the page again)
  NAME.png   the Pareto plot: the measured error against the wall time and
             against the DoFs, a line per pair and algorithm through its meshes,
             the Pareto front, the target and the cheapest choice meeting it

NAME is compare_<scene> unless --name.

Choices: the cartesian product of --pairs, --algorithms, --refinements,
--rn-factors, --rt-factors, --stoppings and --cell-shapes (each defaults to the
scene's own: its pair, its algorithm, refinement 0, factors 1, its `Nonlinear
solver/Stopping`, its cells), or exactly the --choice entries (keys pair,
algorithm, refinement, rn_factor, rt_factor, stopping, cell_shape; a key left
out takes the scene's own). A --choice flag takes one or more choices, the
flag may be repeated: `--choice 'pair=Q1/P1' 'pair=Q2/P1, refinement=1'`,
`--choice pair=Q1/P1 --choice pair=Q2/P1` and `--choice 'pair=Q1/P1,
pair=Q2/P1'` (within one word a key given again, or ';', starts the next
choice) are two runs each. A cell shape sets `Geometry/<model>/Cell shape`
of a built-in geometry: `simplex` splits every cell of the uniformly refined
mesh into 8 triangles (24 tetrahedra), which gives about the DoFs of the
quadrilaterals refined once more; it takes the P pairs (P1/P1, P2/P1, ...),
`hypercube` the Q pairs. A stopping is `fixed` (the loops' own tolerances) or `adaptive` (they
also stop once their error is below a fraction of the estimated
discretisation error, doc/formulation.md "Adaptive stopping"); the reference
stops at the fixed tolerances. An algorithm is `nested` (the three loops of doc/formulation.md
"Nested loops" as fixed points), `newton` (all three folded into the
generalized Newton) or `scene` (the loop methods the scene sets). A
refinement N is added to the scene's `Geometry/<model>/Global refinements`
(negative while the sum stays >= 0). The factors set `Contact/Automatic r_n
factor` and `Automatic r_t factor`: the scene must have r_n (r_t) = automatic
to vary them. --set entries apply to every run, the reference too.

Measured per run: DoFs (displacement + multipliers), load steps, Newton
iterations (those of the attempts that failed and were cut apart, in the CSV's
failed_newton_iterations), the wall time and peak memory of run_summary.csv (runs share the
machine --jobs at a time: their times are comparable with each other), and
the run's own error estimate (`estimated_relative_error` of run_summary.csv:
the residual estimate against the solution's energy norm, doc/formulation.md
"Error estimate"; another quantity than the measured errors, shown beside
them). All at the last load step.

Accuracy, against a closed form where the scene has one: a `half ball` on a
`plane` obstacle whose normal is the vertical axis, frictionless, `linear
elastic`, one body, is Hertz's problem (2D cylinder in plane strain, 3D
sphere): contrib/hertz_errors.py with the run's own normal force and the
scene's E, nu, R gives the relative L2 error of the contact pressure (2D: the
nodal values interpolated linearly against the exact curve; 3D: the RMS of
the nodal errors within 1.5 a), the error of the half-width and of the peak
pressure. The closed form is that of a half-space: the finite body departs
from it by O((a/R)^2), which bounds the errors from below.

Otherwise (or with --against reference) against a reference solution the
tool computes: the scene with --reference-pair (default Q2/P1, stable in 2D
and 3D; Q2/P2's multiplier oscillates between vertices and midsides,
doc/fe_pairs.md; P2/P1 on a scene of simplices), on the scene's own cells, on
the finest requested mesh refined once more (--reference-refinement), with
the scene's r factors and its algorithm (--reference-algorithm: both reach the
same solution, doc/formulation.md "Generalized Newton"; newton is often
faster). The reference must be finer than every choice: a
--reference-refinement not above the finest choice's, or a --reference-pair of
a lower displacement degree than a choice's, is refused.

The reference's own error is estimated and shown (the table's last row, `ref`,
its errors marked ≈; the lines below the table; the CSV's
reference_estimated_error): the tool also runs the reference's pair one and
two levels coarser (a choice that is that run is not run again), and from the
differences d1 (two levels coarser against one) and d0 (one level coarser
against the reference) the observed order q = log2(d1/d0), at most 2, gives
Richardson's estimate d0 / (2^q - 1) (contrib/reference_error.py; with only
two levels q = 1, the estimate d0; differences that do not decrease: unknown).
Beside it the reference run's own pressure estimate (`estimated_pressure_error`,
doc/error_estimator.md); the larger of the two decides which orders stand: a
measured error is the true one within the reference's error E, so where the
errors of two choices next in order differ by at most 3 E the page says that
their order is not to be trusted.

A closed form beside the reference: --hertz 'R=50, bodies=2' (E and nu the
scene's linear elastic ones unless given: 'R=50, bodies=2, E=200000, nu=0.3')
says that the last load step is also Hertz's problem, of one body of radius R
on a rigid plane or of two equal bodies of radius R (R* = R/2, E* = E / (2
(1 - nu^2))), frictionless or with equal materials (their normal and
tangential problems uncouple), the contact zone centred at x = 0 (so not
after a sliding phase: prm/two_cylinders.prm with `--set 'Load stepping/End
time=0.5'`). On a Hertz scene --against reference does the same with the
scene's own constants. The table gets a column of the relative L2 error of
the contact pressure against the closed form (contrib/hertz_errors.py, the
run's own normal force), the reference's too, and the page says whether the
order of the choices against the reference is their order against the
closed form.
At the last load step: the relative errors of the normal and the tangential
contact force (the latter left empty where the reference's is zero, a
frictionless scene), and the relative L2 error of the contact pressure
||p - p_ref|| / ||p_ref||. For it the nodes of both profiles
(profile-NNNNN.csv, reference coordinates; coincident nodes merged) are
placed on the principal line (2D) or plane (3D) of the reference's nodes, and
each profile is made a function there: 2D, linear interpolation between its
nodes along the line; 3D, linear interpolation on the Delaunay triangulation
of its nodes, the nearest node's value outside their hull. The L2 norms are
integrated on the union of both node sets: exactly in 2D (both functions are
linear between consecutive points of the union), on the union's Delaunay
triangulation in 3D. A contact surface that folds over that line or plane
(faces at an angle, two sides of a body) is not measured correctly.

The measured error (--measure: pressure, the relative L2 error of the
contact pressure, by default) is the y axis of the plots and what --target
compares with: the cheapest choice (least wall time) whose measured error is
at most ERROR is printed and marked, or the tool says that none is.

Exit codes: 0 every run converged; 1 a run (or the reference) failed, timed
out or wrote a NaN: it is in the table as failed, the rest is written; 2 a
wrong argument (nothing runs)."""
import argparse
import glob
import itertools
import math
import os
import re
import shlex
import subprocess
import sys
import time
from collections import namedtuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.tri import LinearTriInterpolator, Triangulation

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_map  # noqa: E402
import run_output  # noqa: E402
import tool_cli  # noqa: E402
from hertz_errors import hertz_errors  # noqa: E402
from reference_error import TRUST_FRACTION_TEXT, doubtful_orders, ranking, richardson  # noqa: E402

LOOPS = ("Geometry loop", "Friction loop", "Status loop")
ALGORITHMS = ("nested", "newton", "scene")
STOPPINGS = ("fixed", "adaptive")
# the cells of a built-in geometry (`Geometry/<model>/Cell shape`); `scene` for a mesh file's own
CELL_SHAPES = ("hypercube", "simplex")
Choice = namedtuple("Choice", "pair algorithm refinement rn_factor rt_factor stopping cell_shape")
CHOICE_TYPES = {"pair": str, "algorithm": str, "refinement": int, "rn_factor": float, "rt_factor": float,
                "stopping": str, "cell_shape": str}
# the errors of each kind of accuracy: CSV column, Markdown header
HERTZ_ERRORS = [("pressure_l2_error", "p L2 error"), ("half_width_error", "half-width error"),
                ("peak_error", "peak p error")]
REFERENCE_ERRORS = [("pressure_l2_error", "p L2 error"), ("normal_force_error", "F_n error"),
                    ("tangential_force_error", "F_t error")]
MEASURES = {"pressure": "pressure_l2_error", "normal_force": "normal_force_error",
            "tangential_force": "tangential_force_error", "half_width": "half_width_error", "peak": "peak_error"}
MEASURE_LABELS = {"pressure_l2_error": "relative L2 error of the contact pressure",
                  "normal_force_error": "relative error of the normal force",
                  "tangential_force_error": "relative error of the tangential force",
                  "half_width_error": "relative error of the contact half-width",
                  "peak_error": "relative error of the peak pressure"}
# the part of NAME.md the tool writes; text after it (notes on the results) is kept when it writes again
BEGIN = "<!-- written by contrib/compare.py: begin -->"
END = "<!-- written by contrib/compare.py: end -->"
OUTPUT = robustness_map.OUTPUT_SECTION + robustness_map.nested_set("Output/Write profiles", "true")


def choice_spec(text):
    """argparse type: one or more choices, 'key=value, key=value' with the keys of Choice; a key
    given again, or ';', starts the next choice ('pair=Q1/P1, pair=Q2/P1' is two). A list of
    dicts of typed values."""
    specs = []
    for group in (group for group in text.split(";") if group.strip()):
        spec = {}
        for item in group.split(","):
            key, sep, value = (part.strip() for part in item.partition("="))
            if not sep or key not in CHOICE_TYPES or not value:
                raise argparse.ArgumentTypeError(
                    f"'{item.strip()}' in '{text}' is not key=value with a key of {', '.join(CHOICE_TYPES)}"
                    + ("" if item.strip() else " (a choice with spaces after its commas is one word: quote it)"))
            if key in spec:
                specs.append(spec)
                spec = {}
            try:
                spec[key] = CHOICE_TYPES[key](value)
            except ValueError:
                raise argparse.ArgumentTypeError(f"{key}: '{value}' is not a {CHOICE_TYPES[key].__name__}") from None
        specs.append(spec)
    if not specs:
        raise argparse.ArgumentTypeError(f"'{text}' names no choice")
    for spec in specs:
        checked_choice(spec)
    return specs


def hertz_spec(text):
    """argparse type: 'R=50, bodies=2' (keys R > 0, bodies 1 or 2, E and nu optional); a dict."""
    spec = {}
    for item in (item for item in text.split(",") if item.strip()):
        key, sep, value = (part.strip() for part in item.partition("="))
        try:
            spec[key] = (int if key == "bodies" else float)(value) if sep and key in ("R", "bodies", "E", "nu") \
                else None
        except ValueError:
            spec[key] = None
        if spec[key] is None:
            raise argparse.ArgumentTypeError(f"'{item.strip()}' in '{text}' is not R=number, bodies=1|2, E=number "
                                             "or nu=number")
    if spec.get("R", 0) <= 0 or spec.get("bodies", 1) not in (1, 2) or spec.get("E", 1) <= 0 \
            or not 0 <= spec.get("nu", 0) < 0.5:
        raise argparse.ArgumentTypeError(f"'{text}': R > 0 is needed, bodies is 1 or 2, E > 0, 0 <= nu < 0.5")
    return spec


def checked_choice(spec):
    """The values of one choice that no scene allows: ArgumentTypeError naming the first."""
    if spec.get("algorithm", "nested") not in ALGORITHMS:
        raise argparse.ArgumentTypeError(f"algorithm '{spec['algorithm']}' is not one of {', '.join(ALGORITHMS)}")
    if spec.get("stopping", "fixed") not in STOPPINGS:
        raise argparse.ArgumentTypeError(f"stopping '{spec['stopping']}' is not one of {', '.join(STOPPINGS)}")
    if spec.get("cell_shape", "hypercube") not in CELL_SHAPES:
        raise argparse.ArgumentTypeError(
            f"cell_shape '{spec['cell_shape']}' is not one of {', '.join(CELL_SHAPES)}")
    for key in ("rn_factor", "rt_factor"):
        if spec.get(key, 1) <= 0:
            raise argparse.ArgumentTypeError(f"{key} {spec[key]} is not > 0")


def parameters_of(text, path):
    """{'Section/Entry': value} of parameter text, written to path to be read by run_output."""
    with open(path, "w") as f:
        f.write(text)
    return run_output.read_parameters(path)


class Scene:
    """The scene's entries (the --set ones over the file's over the program's defaults for its dimension)
    and what follows from them: the refinement entry, its own pair and algorithm, whether it is Hertz's
    problem."""

    def __init__(self, executable, path, workdir, settings=()):
        self.path = path
        os.makedirs(workdir, exist_ok=True)
        own = parameters_of(robustness_map.read_scene(path), os.path.join(workdir, "scene.prm"))
        own.update((entry.strip(), value.strip()) for entry, _, value in (s.partition("=") for s in settings))
        self.dim = int(own.get("Dimension", "2"))
        result = subprocess.run([executable, "--print-parameters", str(self.dim)], capture_output=True, text=True)
        if result.returncode != 0:
            raise ValueError(f"'{executable} --print-parameters {self.dim}' exited with {result.returncode}: "
                             f"{(result.stdout + result.stderr).strip()[-300:]}")
        defaults = parameters_of(result.stdout, os.path.join(workdir, f"defaults-{self.dim}d.prm"))
        self.parameters = {**defaults, **own}
        self.pairs = fe_pairs(result.stdout)
        self.geometry = self.parameters["Geometry/Model"]
        self.refinement_entry = f"Geometry/{self.geometry}/Global refinements"
        self.refinements = int(self.parameters[self.refinement_entry])
        self.pair = self.parameters["Contact/Finite element pair"]
        methods = {self.parameters[f"Nonlinear solver/{loop}/Method"] for loop in LOOPS}
        self.algorithm = {frozenset(["fixed point"]): "nested", frozenset(["newton"]): "newton"}.get(
            frozenset(methods), "scene")
        self.stopping = self.parameters["Nonlinear solver/Stopping"]
        self.cell_shape_entry = f"Geometry/{self.geometry}/Cell shape"
        self.cell_shape = self.parameters.get(self.cell_shape_entry, "scene")
        self.automatic = {name: self.parameters[f"Contact/{name}"].strip() == "automatic" for name in ("r_n", "r_t")}
        self.hertz = self.hertz_constants()

    def number(self, entry):
        return float(self.parameters[entry])

    def given_closed_form(self, spec):
        """Hertz's constants (E, nu, R of hertz_errors) of --hertz 'R=..., bodies=2': two equal bodies of
        radius R are one of radius R/2 on a rigid plane with E halved (1/R* = 2/R, 1/E* = 2 (1 - nu^2)/E).
        ValueError if the scene's material is not linear elastic and E or nu is not given."""
        elastic = "Material/linear elastic/"
        if ("E" not in spec or "nu" not in spec) and self.parameters["Material/Model"] != "linear elastic":
            raise ValueError("--hertz takes E and nu from Material/Model = linear elastic; the scene's is "
                             f"{self.parameters['Material/Model']}: give them ('R=50, E=200000, nu=0.3')")
        bodies = spec.get("bodies", 1)
        return {"E": spec.get("E", self.number(elastic + "Young's modulus")) / bodies,
                "nu": spec.get("nu", self.number(elastic + "Poisson's ratio")), "R": spec["R"] / bodies}

    def hertz_constants(self):
        """{'E', 'nu', 'R'} if the scene is Hertz's problem, else None."""
        p = self.parameters
        law = p["Contact/Friction law/Model"]
        threshold = {"Coulomb": "Contact/Friction law/Coulomb/Friction coefficient",
                     "Tresca": "Contact/Friction law/Tresca/Threshold"}.get(law)
        normal = [float(v) for v in p["Obstacle/plane/Normal"].split(",")]
        vertical = normal[-1] > 0 and all(abs(n) <= 1e-12 * normal[-1] for n in normal[:-1])
        bodies = any(p.get(f"Material {k}/Bodies", "").strip() for k in (2, 3))
        if (self.geometry == "half ball" and p["Obstacle/Model"] == "plane" and vertical
                and not p["Contact/Master boundary ids"].strip() and not bodies
                and p["Material/Model"] == "linear elastic" and threshold and self.number(threshold) == 0):
            return {"E": self.number("Material/linear elastic/Young's modulus"),
                    "nu": self.number("Material/linear elastic/Poisson's ratio"),
                    "R": self.number("Geometry/half ball/Radius")}
        return None

    def settings(self, choice):
        """The 'Section/Entry=value' settings of a choice (the algorithm's apart)."""
        settings = [f"Contact/Finite element pair={choice.pair}",
                    f"{self.refinement_entry}={self.refinements + choice.refinement}",
                    f"Contact/Automatic r_n factor={choice.rn_factor!r}",
                    f"Contact/Automatic r_t factor={choice.rt_factor!r}",
                    f"Nonlinear solver/Stopping={choice.stopping}"]
        if choice.cell_shape != "scene":
            settings.append(f"{self.cell_shape_entry}={choice.cell_shape}")
        if choice.algorithm == "nested":
            settings += [f"Nonlinear solver/{loop}/Method=fixed point" for loop in LOOPS]
        return settings

    def text(self, choice, extra_settings):
        """The parameter text of a run of the choice (the scene's step cuts kept)."""
        return robustness_map.build_scene(self.path, self.settings(choice) + list(extra_settings),
                                          "newton" if choice.algorithm == "newton" else "nested",
                                          int(self.parameters["Load stepping/Maximum step cuts"])) + OUTPUT


def fe_pairs(print_parameters):
    """The pair names that --print-parameters documents above `set Finite element pair`."""
    lines = print_parameters.splitlines()
    for i, line in enumerate(lines):
        if re.match(r"\s*set Finite element pair\s*=", line):
            names = []
            while i > 0 and lines[i - 1].strip().startswith("#"):
                i -= 1
                names += re.findall(r"^\s*#\s*'([^']+)':", lines[i])
            return set(names)
    return set()


def choices_of(args, scene, parser):
    """The choices to run, checked against the scene (a usage error names what is wrong)."""
    own = Choice(scene.pair, scene.algorithm, 0, 1.0, 1.0, scene.stopping, scene.cell_shape)
    if args.choice:
        lists = [k for k in ("pairs", "algorithms", "refinements", "rn_factors", "rt_factors", "stoppings",
                             "cell_shapes") if getattr(args, k)]
        if lists:
            parser.error(f"--choice lists the runs itself: it excludes --{lists[0].replace('_', '-')}")
        choices = [own._replace(**spec) for word in args.choice for spec in word]
    else:
        lists = [getattr(args, k) or [getattr(own, f)] for k, f in (
            ("pairs", "pair"), ("algorithms", "algorithm"), ("refinements", "refinement"),
            ("rn_factors", "rn_factor"), ("rt_factors", "rt_factor"), ("stoppings", "stopping"),
            ("cell_shapes", "cell_shape"))]
        choices = [Choice(*values) for values in itertools.product(*lists)]
    choices = list(dict.fromkeys(choices))  # the same choice once
    for choice in choices:
        if scene.pairs and choice.pair not in scene.pairs:
            parser.error(f"pair '{choice.pair}' is not one of {', '.join(sorted(scene.pairs))}")
        if choice.cell_shape != scene.cell_shape and scene.cell_shape == "scene":
            parser.error(f"cell shape '{choice.cell_shape}': the scene's geometry `{scene.geometry}` has no "
                         "Cell shape entry (a mesh file's cells are its own)")
        if choice.cell_shape in CELL_SHAPES and simplex_pair(choice.pair) != (choice.cell_shape == "simplex"):
            parser.error(f"pair '{choice.pair}' with cell shape '{choice.cell_shape}': the P pairs are for "
                         "simplices, the Q pairs for hypercubes")
        if scene.refinements + choice.refinement < 0:
            parser.error(f"refinement {choice.refinement}: the scene's {scene.refinement_entry} is "
                         f"{scene.refinements}, so it would be negative")
        for name, factor in (("r_n", choice.rn_factor), ("r_t", choice.rt_factor)):
            if factor != 1 and not scene.automatic[name]:
                parser.error(f"an {name} factor needs Contact/{name} = automatic in the scene "
                             f"(it is {scene.parameters['Contact/' + name]})")
    return choices


def simplex_pair(pair):
    """Whether a pair is for triangles / tetrahedra (P1/P1, P2/P1, ...) rather than Q_k cells."""
    return pair.startswith("P")


def slug(text):
    return re.sub(r"[^\w.+-]+", "_", text).strip("_")


def describe(choice, scene):
    text = f"{choice.pair}, {choice.algorithm}, {scene.refinement_entry.split('/')[-1].lower()} " \
           f"{scene.refinements + choice.refinement}"
    if choice.rn_factor != 1 or choice.rt_factor != 1:
        text += f", r_n x{choice.rn_factor:g}, r_t x{choice.rt_factor:g}"
    if choice.stopping != "fixed":
        text += f", {choice.stopping} stopping"
    if choice.cell_shape != scene.cell_shape:
        text += f", {choice.cell_shape} cells"
    return text


def read_table(path):
    """The rows of a CSV file, numbers as floats."""
    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    return run_output.read_rows(path, value)


def run_results(case_dir):
    """What the tool reads of a run that converged: run_summary.csv, the last row of statistics.csv and
    the last profile. ValueError if a file is missing or empty."""
    output = os.path.join(case_dir, "output")
    try:
        summary = read_table(os.path.join(output, "run_summary.csv"))[0]
        last = read_table(os.path.join(output, "statistics.csv"))[-1]
        profiles = sorted(glob.glob(os.path.join(output, "profile-*.csv")))
        profile = read_table(profiles[-1]) if profiles else []
    except (OSError, IndexError) as error:
        raise ValueError(f"the output of {case_dir} is incomplete: {error}") from None
    return {"cells": int(summary["cells"]), "dofs": int(summary["displacement_dofs"] + summary["multiplier_dofs"]),
            "load_steps": int(summary["load_steps"]), "newton_iterations": int(summary["newton_iterations"]),
            "failed_newton_iterations": int(summary["failed_attempt_newton_iterations"]),
            "wall_time_s": summary["wall_time_s"], "peak_memory_MiB": summary["peak_memory_MiB"],
            "estimated_relative_error": summary["estimated_relative_error"],
            "estimated_pressure_error": last.get("estimated_pressure_error"),
            "normal_force_N": last["normal_force_N"], "tangential_force_N": last["tangential_force_N"],
            "profile": profile}


# --- the contact pressure of a run against the reference's ---------------------------------------

def surface_frame(dim, points):
    """Centre and the dim - 1 principal directions (rows) of points on the contact surface."""
    centre = points.mean(axis=0)
    _, _, directions = np.linalg.svd(points - centre, full_matrices=False)
    return centre, directions[:dim - 1]


def surface_nodes(dim, profile, frame, tolerance):
    """The profile's nodes in the surface's coordinates (n x (dim - 1)) and their pressures,
    nodes closer than tolerance in every coordinate merged (their mean pressure)."""
    names = ["x_mm", "y_mm", "z_mm"][:dim]
    points = np.array([[row[n] for n in names] for row in profile], dtype=float)
    pressure = np.array([row["contact_pressure_MPa"] for row in profile], dtype=float)
    centre, directions = frame
    coordinates = (points - centre) @ directions.T
    keys, index = np.unique(np.round(coordinates / tolerance).astype(np.int64), axis=0, return_inverse=True)
    index = index.reshape(-1)
    merged = np.zeros((len(keys), dim - 1))
    np.add.at(merged, index, coordinates)
    count = np.bincount(index, minlength=len(keys)).astype(float)
    return merged / count[:, None], np.bincount(index, weights=pressure, minlength=len(keys)) / count


def interpolant(points, values):
    """The linear interpolant on the Delaunay triangulation of 2D points; the nearest point's value outside."""
    linear = LinearTriInterpolator(Triangulation(points[:, 0], points[:, 1]), values)

    def evaluate(at):
        result = linear(at[:, 0], at[:, 1])
        found = np.ma.getmaskarray(result)
        out = np.ma.filled(result, 0.0).astype(float)
        for i in np.flatnonzero(found):
            out[i] = values[np.argmin(((points - at[i]) ** 2).sum(axis=1))]
        return out
    return evaluate


def pressure_l2_error(dim, profile, reference):
    """Relative L2 error of the contact pressure of profile against reference (rows of profile CSVs);
    NaN if the reference has no pressure."""
    names = ["x_mm", "y_mm", "z_mm"][:dim]
    reference_points = np.array([[row[n] for n in names] for row in reference], dtype=float)
    frame = surface_frame(dim, reference_points)
    tolerance = 1e-9 * max(np.ptp(reference_points, axis=0).max(), 1e-300)
    s_h, p_h = surface_nodes(dim, profile, frame, tolerance)
    s_r, p_r = surface_nodes(dim, reference, frame, tolerance)
    if dim == 2:
        s_h, s_r = s_h[:, 0], s_r[:, 0]
        order_h, order_r = np.argsort(s_h), np.argsort(s_r)
        grid = np.union1d(s_h, s_r)
        error = np.interp(grid, s_h[order_h], p_h[order_h]) - np.interp(grid, s_r[order_r], p_r[order_r])
        exact = np.interp(grid, s_r[order_r], p_r[order_r])
        lengths = np.diff(grid)

        def integral(f):  # of f^2, f linear on each interval
            return np.sum(lengths / 3 * (f[:-1] ** 2 + f[:-1] * f[1:] + f[1:] ** 2))
    else:
        union, _ = surface_nodes(dim, profile + reference, frame, tolerance)
        triangulation = Triangulation(union[:, 0], union[:, 1])
        exact = interpolant(s_r, p_r)(union)
        error = interpolant(s_h, p_h)(union) - exact
        corners = union[triangulation.triangles]
        edges = corners[:, 1:] - corners[:, :1]
        areas = 0.5 * np.abs(edges[:, 0, 0] * edges[:, 1, 1] - edges[:, 0, 1] * edges[:, 1, 0])

        def integral(f):  # of f^2, f linear on each triangle
            a, b, c = f[triangulation.triangles].T
            return np.sum(areas / 6 * (a * a + b * b + c * c + a * b + b * c + c * a))
    norm = integral(exact)
    return math.sqrt(integral(error) / norm) if norm > 0 else math.nan


def relative(value, reference, scale):
    """|value - reference| / |reference|, None where |reference| is zero against scale."""
    return abs(value - reference) / abs(reference) if abs(reference) > 1e-12 * abs(scale) else None


def accuracy(scene, results, reference):
    """The errors of a run's results: against Hertz if scene.hertz, else against the reference's results
    (None where there is no reference)."""
    if scene.hertz:
        try:
            errors = hertz_errors(scene.dim, results["normal_force_N"], results["profile"], **scene.hertz)
        except ValueError:  # no node in contact
            return {"pressure_l2_error": math.nan, "half_width_error": math.nan, "peak_error": math.nan}
        return {"pressure_l2_error": errors["l2_error"], "half_width_error": errors["half_width_error"],
                "peak_error": errors["peak_error"], "hertz_half_width_mm": errors["a_hertz_mm"]}
    if reference is None or not results["profile"]:
        return {}
    normal = reference["normal_force_N"]
    return {"pressure_l2_error": pressure_l2_error(scene.dim, results["profile"], reference["profile"]),
            "normal_force_error": relative(results["normal_force_N"], normal, normal),
            "tangential_force_error": relative(results["tangential_force_N"], reference["tangential_force_N"],
                                               normal)}


# --- output -------------------------------------------------------------------------------------

def percent(value):
    if value is None:
        return "—"
    if value == math.inf:
        return "unknown"
    return "NaN" if not math.isfinite(value) else f"{100 * value:.3g} %"


def number(value, digits=3):
    if value is None:
        return "—"
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def cheapest(rows, key, target):
    """The converged row of least wall time whose rows[key] is at most target, or None."""
    meeting = [r for r in rows if r["outcome"] == "converged" and r.get(key) is not None
               and math.isfinite(r[key]) and r[key] <= target]
    return min(meeting, key=lambda r: r["wall_time_s"]) if meeting else None


def pareto_front(points):
    """The points (x, y) that no other point beats in both x and y, by increasing x."""
    front, best = [], math.inf
    for x, y in sorted(points):
        if y < best:
            front.append((x, y))
            best = y
    return front


# where each series writes the refinement beside its points (offset points), so that series that
# fall on each other stay readable
OFFSETS = [(4, 4), (4, -11), (-11, 4), (-11, -11)]


def plot(rows, key, scene_name, target, best, png_path, reference_error=None):
    """Error against wall time and against DoFs, a line per (pair, algorithm, factors) through its meshes;
    the reference's estimated error a grey band (errors below it are not measured)."""
    figure = Figure(figsize=(13, 5.2), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(1, 2)
    plotted = [r for r in rows if r["outcome"] == "converged" and r.get(key) is not None
               and math.isfinite(r[key]) and r[key] > 0]
    series = {}
    for r in sorted(plotted, key=lambda r: r["refinement"]):
        series.setdefault((r["pair"], r["algorithm"], r["rn_factor"], r["rt_factor"], r["stopping"]), []).append(r)
    pairs = sorted({s[0] for s in series})
    # a line style per (factors, stopping)
    variants = sorted({s[2:] for s in series})
    markers = {"nested": "o", "newton": "s", "scene": "^"}
    styles = ["-", "--", ":", "-."]
    colours = [f"C{i % 10}" for i in range(len(pairs))]
    for ax, x_key, x_label in zip(axes, ("wall_time_s", "dofs"),
                                  ("wall time of the run (s)", "DoFs (displacement + multipliers)")):
        annotated = set()
        for number, ((pair, algorithm, rn, rt, stopping), runs) in enumerate(series.items()):
            label = f"{pair}, {algorithm}"
            if len({v[:2] for v in variants}) > 1:
                label += f", r_n x{rn:g}, r_t x{rt:g}"
            if len({v[2] for v in variants}) > 1:
                label += f", {stopping} stopping"
            ax.plot([r[x_key] for r in runs], [r[key] for r in runs], marker=markers[algorithm],
                    color=colours[pairs.index(pair)],
                    linestyle=styles[variants.index((rn, rt, stopping)) % len(styles)],
                    mfc="none" if algorithm == "newton" else None, label=label)
            for r in runs:
                if (r[x_key], r[key]) in annotated:  # another algorithm's run on the same point
                    continue
                annotated.add((r[x_key], r[key]))
                ax.annotate(str(r["global_refinements"]), (r[x_key], r[key]), textcoords="offset points",
                            xytext=OFFSETS[number % len(OFFSETS)], fontsize=7, color=colours[pairs.index(pair)])
        front = pareto_front([(r[x_key], r[key]) for r in plotted])
        if len(front) > 1:
            ax.step(*zip(*front), where="post", color="black", alpha=0.35, linewidth=4, zorder=0,
                    label="Pareto front")
        if target is not None:
            ax.axhline(target, color="red", linestyle=":", linewidth=1, label=f"target {target:g}")
        if reference_error is not None and 0 < reference_error < math.inf and plotted:
            ax.axhspan(min(reference_error, min(r[key] for r in plotted)) / 2, reference_error, color="grey",
                       alpha=0.2, zorder=0, label=f"within the reference's estimated error ({percent(reference_error)})")
        if best is not None:
            ax.plot(best[x_key], best[key], "*", markersize=18, mfc="none", mec="red", mew=1.5,
                    label="cheapest meeting the target")
        if not plotted:
            ax.text(0.5, 0.5, "no run with a measured error", transform=ax.transAxes, ha="center", color="grey")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(x_label)
        ax.set_ylabel(MEASURE_LABELS[key])
        ax.grid(True, which="both", alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(fontsize=8, loc="lower left")
    failed = sum(r["outcome"] != "converged" for r in rows)
    figure.suptitle(f"{scene_name}: error against cost (numbers: global refinements)"
                    + (f"; {failed} failed run(s) not shown" if failed else ""))
    figure.savefig(png_path, dpi=110)


TEXT_COLUMNS = ("pair", "algorithm", "stopping", "cells", "outcome", "target")  # left-aligned in the page's table


def markdown(rows, error_columns, key, target, best, scene, reference_lines, basis, command, png_name, show_factors,
             show_stopping, show_cells, reference_row=None):
    """The page; reference_row (the reference's results and its estimated errors, `estimates`) is the table's
    last row, its errors marked ≈ as estimates."""
    header = ["#", "pair", "algorithm", *(["stopping"] if show_stopping else []), *(["cells"] if show_cells else []),
              "global ref.",
              *(["r_n factor", "r_t factor"] if show_factors else []),
              "outcome", "DoFs", "Newton it.", "wall (s)", "peak memory (MiB)",
              *[title for _, title in error_columns], "estimate (energy, rel.)", *(["target"] if target else [])]
    scene_algorithm = scene.algorithm if scene.algorithm != "scene" else "of its own loop methods"
    lines = [BEGIN, f"# Cost against accuracy: `{os.path.basename(scene.path)}`", "",
             f"Generated by `{command}`.", "",
             f"Scene `{tool_cli.shown(scene.path)}`: {scene.dim}D, geometry `{scene.geometry}` with "
             f"{scene.refinement_entry.split('/')[-1]} = {scene.refinements}, pair `{scene.pair}`, "
             f"algorithm {scene_algorithm}. Each run is the scene with the choice's pair, algorithm, stopping, cell "
             "shape, global refinements and r factors; runs share the machine (`--jobs`), so their wall times compare with "
             "each other.", "", basis, "",
             f"The measured error of the plot and of the target: the {MEASURE_LABELS[key]}. The estimate is "
             "the run's own `estimated_relative_error` (run_summary.csv: the residual estimate against the "
             "solution's energy norm), another quantity, shown beside it. Errors and forces are those of the "
             "last load step.", "",
             "| " + " | ".join(header) + " |",
             "|" + "".join("---|" if title in TEXT_COLUMNS else "---:|" for title in header)]
    for r in rows + ([reference_row] if reference_row else []):
        ok = r["outcome"] == "converged"
        cells = [str(r["index"]), r["pair"], r["algorithm"], *([r["stopping"]] if show_stopping else []),
                 *([r["cell_shape"]] if show_cells else []), str(r["global_refinements"])]
        if show_factors:
            cells += [f"{r['rn_factor']:g}", f"{r['rt_factor']:g}"]
        cells.append(r["outcome"] if ok else f"**failed: {r['outcome']}** (exit code {number(r['exit_code'])})")
        cells += [number(r.get("dofs")), number(r.get("newton_iterations")),
                  number(r.get("wall_time_s")), number(r.get("peak_memory_MiB"), 4)]
        if r is reference_row:
            cells += [("≈ " if math.isfinite(r["estimates"][c]) else "") + percent(r["estimates"][c])
                      if c in r["estimates"] else percent(r.get(c))
                      for c, _ in error_columns]
        else:
            cells += [percent(r.get(c)) if ok else "—" for c, _ in error_columns]
        cells.append(percent(r.get("estimated_relative_error")) if ok else "—")
        if target:
            cells.append("**cheapest**" if r is best else "meets" if r.get("meets_target") else "")
        if r is best:
            cells = [f"**{c}**" if c and not c.startswith("**") else c for c in cells]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    for line in reference_lines:
        lines += [line, ""]
    if target:
        lines += [target_sentence(best, key, target, rows), ""]
    lines += [f"![error against wall time and DoFs]({png_name})", "",
              "How the errors are measured, and the options: `contrib/compare.py --help`.", END]
    return "\n".join(lines) + "\n"


def target_sentence(best, key, target, rows):
    if best is not None:
        return (f"Target {MEASURE_LABELS[key]} ≤ {percent(target)}: the cheapest choice meeting it is "
                f"#{best['index']} ({best['label']}): {percent(best[key])}, {best['wall_time_s']:.3g} s, "
                f"{best['dofs']} DoFs, {best['newton_iterations']} Newton iterations.")
    measured = [r for r in rows if r.get(key) is not None and math.isfinite(r[key])]
    closest = min(measured, key=lambda r: r[key]) if measured else None
    return (f"Target {MEASURE_LABELS[key]} ≤ {percent(target)}: no choice meets it"
            + (f" (the smallest error is {percent(closest[key])}, #{closest['index']} ({closest['label']}))."
               if closest else "."))


def regenerating_command(args):
    """The command line as a page shows it: the scene relative to the repository; with --doc without
    --executable (its default, build/stabilized_lagrangian) and --workdir."""
    words, skip = [], False
    for word in sys.argv[1:]:
        if skip:
            skip = False
            continue
        if args.doc and word.split("=", 1)[0] in ("--executable", "--workdir"):
            skip = "=" not in word
            continue
        words.append(tool_cli.shown(word) if word == args.scene else word)
    return "contrib/compare.py " + shlex.join(words)


def algorithm_name(algorithm, scene):
    if algorithm != "scene":
        return algorithm
    return f"the scene's ({scene.algorithm})" if scene.algorithm != "scene" else "the scene's loop methods"


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", type=tool_cli.existing_file, help="the parameter file (.prm)")
    parser.add_argument("--executable", type=tool_cli.executable,
                        default=os.path.join(tool_cli.ROOT, "build", "stabilized_lagrangian"),
                        help="the program (default: build/stabilized_lagrangian of the repository)")
    parser.add_argument("--pairs", nargs="+", metavar="PAIR", help="finite element pairs (default: the scene's)")
    parser.add_argument("--algorithms", nargs="+", choices=ALGORITHMS, metavar="ALGORITHM",
                        help="nested, newton or scene (default: the scene's)")
    parser.add_argument("--refinements", nargs="+", type=int, metavar="N",
                        help="levels added to the scene's global refinements (default: 0)")
    parser.add_argument("--rn-factors", nargs="+", type=tool_cli.positive_float, metavar="F",
                        help="Contact/Automatic r_n factor values (default: 1)")
    parser.add_argument("--rt-factors", nargs="+", type=tool_cli.positive_float, metavar="F",
                        help="Contact/Automatic r_t factor values (default: 1)")
    parser.add_argument("--stoppings", nargs="+", choices=STOPPINGS, metavar="STOPPING",
                        help="fixed or adaptive: Nonlinear solver/Stopping (default: the scene's)")
    parser.add_argument("--cell-shapes", nargs="+", choices=CELL_SHAPES, metavar="SHAPE",
                        help="hypercube or simplex: Geometry/<model>/Cell shape of a built-in geometry "
                             "(default: the scene's)")
    parser.add_argument("--choice", action="extend", nargs="+", type=choice_spec, default=[],
                        metavar="'key=value, ...'",
                        help="the runs, instead of the product of the lists: one or more choices per flag "
                             "(separate words, or one word where ';' or a key given again starts the next "
                             "choice), the flag repeatable; keys pair, algorithm, refinement, rn_factor, "
                             "rt_factor, stopping, cell_shape; the scene's own for a key left out")
    parser.add_argument("--set", action="append", default=[], type=tool_cli.setting,
                        metavar="'Section/Sub/Entry=value'", help="an entry set in every run, repeatable")
    parser.add_argument("--measure", choices=sorted(MEASURES), default="pressure",
                        help="the error plotted and compared with --target (default: %(default)s)")
    parser.add_argument("--target", type=tool_cli.positive_float, metavar="ERROR",
                        help="relative error (0.01 = 1 %%): mark the cheapest choice that meets it")
    parser.add_argument("--reference-pair", metavar="PAIR",
                        help="pair of the reference solution, for a scene without a closed form (default: Q2/P1, "
                             "on a simplex mesh P2/P1)")
    parser.add_argument("--reference-algorithm", choices=ALGORITHMS, default="scene",
                        help="its algorithm (default: %(default)s, the scene's loop methods)")
    parser.add_argument("--reference-refinement", type=int, metavar="N",
                        help="its level added to the scene's global refinements (default: the finest choice's + 1)")
    parser.add_argument("--hertz", type=hertz_spec, metavar="'R=..., bodies=1|2'",
                        help="the scene's last load step is also Hertz's problem (frictionless, or two equal "
                             "bodies whose normal and tangential problems uncouple): bodies of radius R, E and nu "
                             "the scene's linear elastic ones unless given; the choices' and the reference's "
                             "pressure errors against the closed form are shown beside those against the reference")
    parser.add_argument("--against", choices=("closed-form", "reference"), default="closed-form",
                        help="what a Hertz scene's errors are measured against (default: %(default)s; reference: "
                             "the closed form beside it, to check the reference)")
    parser.add_argument("--jobs", type=tool_cli.positive_int, default=os.cpu_count(),
                        help="runs at a time (default: %(default)s)")
    parser.add_argument("--timeout", type=tool_cli.positive_float, default=3600,
                        help="seconds per run before it is killed (default: %(default)s)")
    parser.add_argument("--workdir", help="where the runs are (default: /tmp/compare/<scene>)")
    parser.add_argument("--name", help="name of the result files (default: compare_<scene>)")
    tool_cli.add_output_arguments(parser, None, ["NAME.md", "NAME.csv", "NAME.png"])
    args = parser.parse_args()
    args.scene_name = os.path.splitext(os.path.basename(args.scene))[0]
    args.workdir = os.path.abspath(args.workdir or os.path.join("/tmp/compare", slug(args.scene_name)))
    args.output = args.output or args.workdir
    tool_cli.check_output(parser, args)
    args.name = args.name or f"compare_{slug(args.scene_name)}"
    if "/" in args.name or args.name in ("", ".", ".."):
        parser.error(f"argument --name: '{args.name}' is not a file name")
    return parser, args


def plan(parser, args):
    """The scene, the runs {key: choice} (key 0 the reference, 1, 2, ... the choices, -1, -2 the reference's
    coarser levels that are not choices), their parameter texts and the reference's ladder (the keys of the
    reference and of its coarser levels, finest first; empty against a closed form); a usage error for what
    does not fit the scene."""
    try:
        scene = Scene(args.executable, args.scene, args.workdir, args.set)
    except (ValueError, KeyError) as error:
        parser.error(f"the scene {args.scene}: {error}")
    runs = dict(enumerate(choices_of(args, scene, parser), 1))
    ladder = []
    scene.closed_form = None  # Hertz's constants measured beside the reference
    if args.hertz and scene.hertz:
        parser.error("--hertz: the scene is Hertz's problem, its closed form is known already")
    if args.against == "reference" and scene.hertz:
        scene.closed_form, scene.hertz = scene.hertz, None
    elif args.hertz:
        try:
            scene.closed_form = scene.given_closed_form(args.hertz)
        except (ValueError, KeyError) as error:
            parser.error(str(error))
    key = MEASURES[args.measure]
    own = dict(HERTZ_ERRORS if scene.hertz else REFERENCE_ERRORS)
    if key not in own:
        parser.error(f"--measure {args.measure}: against {'Hertz' if scene.hertz else 'the reference'} the "
                     f"measures are {', '.join(m for m, k in MEASURES.items() if k in own)}")
    if not scene.hertz:
        if args.reference_pair is None:
            args.reference_pair = "P2/P1" if simplex_pair(scene.pair) else "Q2/P1"
        if scene.pairs and args.reference_pair not in scene.pairs:
            parser.error(f"--reference-pair '{args.reference_pair}' is not one of {', '.join(sorted(scene.pairs))}")
        finest = max(c.refinement for c in runs.values())
        level = finest + 1 if args.reference_refinement is None else args.reference_refinement
        if level <= finest:
            parser.error(f"--reference-refinement {level}: the reference must be finer than every choice, at "
                         f"least {finest + 1} (the finest choice's refinement is {finest})")
        degree = max(pair_degree(c.pair) for c in runs.values())
        if pair_degree(args.reference_pair) < degree:
            parser.error(f"--reference-pair {args.reference_pair}: the reference must be of at least the "
                         f"choices' highest displacement degree, {degree}")
        runs[0] = Choice(args.reference_pair, args.reference_algorithm, level, 1.0, 1.0, "fixed", scene.cell_shape)
        ladder = reference_ladder(scene, runs)
    try:
        texts = {k: scene.text(c, args.set) for k, c in runs.items()}
    except ValueError as error:
        parser.error(str(error))
    return scene, runs, texts, ladder


def pair_degree(pair):
    """The displacement degree of a pair: Q2/P1 -> 2."""
    found = re.match(r"[QP](\d+)", pair)
    return int(found.group(1)) if found else 1


def reference_ladder(scene, runs):
    """The reference (key 0) and the same pair one and two levels coarser, where the scene's refinements
    allow: a choice's key where a choice is that run, else a new key -1, -2 in runs. Keys, finest first."""
    def resolved(choice):  # `scene` is the scene's own algorithm
        return choice._replace(algorithm=scene.algorithm) if choice.algorithm == "scene" else choice
    ladder = [0]
    for step in (1, 2):
        coarser = runs[0]._replace(refinement=runs[0].refinement - step)
        if scene.refinements + coarser.refinement < 0:
            break
        same = [k for k, c in runs.items() if k > 0 and resolved(c) == resolved(coarser)]
        if not same:
            runs[-step] = coarser
        ladder.append(same[0] if same else -step)
    return ladder


def run_all(args, scene, runs, texts):
    """Run them, the reference and the finest meshes first (the longest start first); {key: (runner's row,
    directory, results or None)}."""
    names = {0: "reference", -1: "reference one level coarser", -2: "reference two levels coarser"}
    labels = {k: (names[k] + " " if k <= 0 else f"#{k} ") + describe(c, scene) for k, c in runs.items()}
    directories = {k: os.path.join(args.workdir, slug(names[k]) if k <= 0 else f"{k:02d}_{slug(describe(c, scene))}")
                   for k, c in runs.items()}
    order = sorted(runs, key=lambda k: (k != 0, -runs[k].refinement, runs[k].pair, k))
    coarser = sum(k < 0 for k in runs)
    print(f"{sum(k > 0 for k in runs)} choice(s){' and the reference' if 0 in runs else ''}"
          f"{f' (and {coarser} coarser level(s) of it)' if coarser else ''} of {args.scene}, "
          f"{args.jobs} at a time, in {args.workdir}", flush=True)
    start = time.monotonic()

    def label(k, row):
        text = f"{labels[k]}: {row['outcome']}"
        if row["outcome"] != "converged":
            text += f" (exit code {row['exit_code']}; log {os.path.join(directories[k], 'log.txt')})"
        return text + f", {row['wall_time_s']:.1f} s" + (", NaN in output" if row["nan_in_output"] else "")

    ran = robustness_map.run_cases(args.executable, [(k, texts[k], directories[k]) for k in order],
                                   args.jobs, args.timeout, label)
    print(f"all runs done in {time.monotonic() - start:.0f} s", flush=True)
    done = {}
    for k, row in ran.items():
        results = None
        if row["outcome"] == "converged" and row["nan_in_output"]:
            row["outcome"] = "error"  # a NaN in the output is a bug, as in robustness_map
        if row["outcome"] == "converged":
            try:
                results = run_results(directories[k])
            except ValueError as error:
                print(error)
                row["outcome"] = "error"
        done[k] = (row, directories[k], results)
    return done


def table_rows(scene, runs, done):
    """A row per choice: the choice, the runner's outcome, the run's results and errors."""
    reference = done[0][2] if 0 in done else None
    rows = []
    for k in sorted(k for k in runs if k > 0):
        choice, (ran, _, results) = runs[k], done[k]
        row = {"index": k, "label": describe(choice, scene), **choice._asdict(),
               "global_refinements": scene.refinements + choice.refinement, "outcome": ran["outcome"],
               "exit_code": ran["exit_code"], "process_time_s": ran["wall_time_s"]}
        if results:
            row.update({name: value for name, value in results.items() if name != "profile"})
            row.update(accuracy(scene, results, reference))
            if scene.closed_form:
                row["hertz_pressure_l2_error"] = closed_form_error(scene, results)
        rows.append(row)
    return rows


def closed_form_error(scene, results):
    """The relative L2 error of a run's last contact pressure against Hertz's closed form of --hertz, with
    the run's own normal force (contrib/hertz_errors.py); NaN without a node in contact."""
    try:
        return hertz_errors(scene.dim, results["normal_force_N"], results["profile"], **scene.closed_form)[
            "l2_error"]
    except ValueError:
        return math.nan


def reference_estimate(scene, runs, done, ladder):
    """The reference's estimated errors {error column: (estimate, observed order, how, differences)}, from
    the differences between the levels of its ladder (contrib/reference_error.py); {} if it failed."""
    results = [done[k][2] for k in ladder]
    if not results or results[0] is None:
        return {}
    differences = []
    for fine, coarse in zip(results, results[1:]):
        if coarse is None:
            break
        differences.append(accuracy(scene, coarse, fine))
    estimates = {}
    for column, _ in REFERENCE_ERRORS:
        measured = [d.get(column) for d in differences]
        fine, coarse = (measured + [None, None])[:2]
        estimates[column] = (*richardson(fine, coarse), [m for m in measured if m is not None])
    return estimates


def reference_notes(scene, runs, done, ladder, estimates, rows, key):
    """The page's lines on the reference's own error, on the order of the choices it decides, and, with
    --hertz, the reference's error and the choices' order against the closed form."""
    reference = done[0][2]
    if reference is None:
        return []
    levels = ", ".join(str(scene.refinements + runs[k].refinement) for k in ladder[::-1] if done[k][2] is not None)
    estimate, order, how, differences = estimates[key]
    own = reference.get("estimated_pressure_error")
    if key != "pressure_l2_error" or not isinstance(own, float) or not math.isfinite(own):
        own = None
    error = estimate if own is None else max(estimate, own)
    line = (f"The reference's estimated error ({MEASURE_LABELS[key]}): **{percent(estimate)}** (its levels "
            f"{levels} of `{runs[0].pair}` differ by {' and '.join(percent(d) for d in differences[::-1]) or '—'}: "
            f"{how}; contrib/reference_error.py)")
    if own is not None:
        line += f"; the run's own pressure estimate {percent(own)} (doc/error_estimator.md)"
    if scene.closed_form:
        line += f"; against Hertz's closed form {percent(closed_form_error(scene, reference))}"
    lines = [line + "."]
    values = [(f"#{r['index']}", r.get(key)) for r in rows if r["outcome"] == "converged"]
    doubts = doubtful_orders(values, error)
    if doubts:
        lines.append(
            f"**The order of the choices is not to be trusted**: the reference's estimated error, "
            f"{percent(error)}, is not below {TRUST_FRACTION_TEXT} of the difference between the errors of "
            + ", of ".join(f"{a} and {b} ({percent(gap)})" for a, b, gap in doubts)
            + ". A finer reference (`--reference-refinement`) or choices further apart decide it.")
    elif len(ranking(values)) > 1:
        lines.append(f"The reference's estimated error, {percent(error)}, is below {TRUST_FRACTION_TEXT} of every "
                     "difference between the errors of choices next in order: the order stands.")
    if scene.closed_form:
        hertz = [(f"#{r['index']}", r.get("hertz_pressure_l2_error")) for r in rows if r["outcome"] == "converged"]
        by_reference, by_hertz = ranking(values), ranking(hertz)
        lines.append(f"Order by the {MEASURE_LABELS[key]} against the reference: {', '.join(by_reference)}; by "
                     f"the relative L2 error of the contact pressure against Hertz's closed form: "
                     f"{', '.join(by_hertz)}: {'the same' if by_reference == by_hertz else '**a different**'} order.")
    return lines


def accuracy_text(scene, runs, done, rows):
    """The page's sentence on what the errors are measured against, and the reference's line (or None)."""
    if scene.hertz:
        finest = max((r for r in rows if r.get("hertz_half_width_mm")), key=lambda r: r["dofs"], default=None)
        ratio = f" (here a/R = {finest['hertz_half_width_mm'] / scene.hertz['R']:.3g})" if finest else ""
        return ("Accuracy against Hertz's closed form (the scene is a frictionless linear elastic half "
                f"{'cylinder' if scene.dim == 2 else 'ball'}, R = {scene.hertz['R']:g} mm, on a rigid plane), "
                "with each run's own normal force: contrib/hertz_errors.py. The closed form is a half-space's: "
                f"the finite body departs from it by O((a/R)²){ratio}."), None
    choice, (ran, directory, reference) = runs[0], done[0]
    basis = (f"Accuracy against a reference solution computed by the tool: pair `{choice.pair}`, "
             f"{scene.refinement_entry.split('/')[-1]} = {scene.refinements + choice.refinement}, algorithm "
             f"{algorithm_name(choice.algorithm, scene)}; the forces' relative errors and the relative L2 error "
             "of the contact pressure profile (each profile interpolated linearly along the contact surface) at "
             "the last load step.")
    if reference is None:
        return basis, (f"**The reference run failed** ({ran['outcome']}, exit code {ran['exit_code']}; "
                       f"{os.path.join(directory, 'log.txt')}): no error is measured.")
    return basis, (f"Reference: `{choice.pair}`, {scene.refinement_entry.split('/')[-1]} = "
                   f"{scene.refinements + choice.refinement}, {reference['dofs']} DoFs, "
                   f"{reference['newton_iterations']} Newton iterations, "
                   f"{reference['wall_time_s']:.3g} s, {reference['peak_memory_MiB']:.4g} MiB; "
                   f"F_n = {reference['normal_force_N']:.7g} N, F_t = {reference['tangential_force_N']:.7g} N"
                   f"{' per mm of thickness' if scene.dim == 2 else ''}; its estimate "
                   f"{percent(reference['estimated_relative_error'])}.")


def main():
    parser, args = parse_arguments()
    scene, runs, texts, ladder = plan(parser, args)
    done = run_all(args, scene, runs, texts)
    rows = table_rows(scene, runs, done)
    key = MEASURES[args.measure]
    reference = done[0][2] if 0 in done else None
    estimates = reference_estimate(scene, runs, done, ladder) if ladder else {}
    notes = reference_notes(scene, runs, done, ladder, estimates, rows, key) if estimates else []
    for r in rows:
        if estimates:
            r["reference_estimated_error"] = estimates[key][0]
    error_columns = HERTZ_ERRORS if scene.hertz else [
        c for c in REFERENCE_ERRORS if c[0] != "tangential_force_error" or reference is None
        or relative(0.0, reference["tangential_force_N"], reference["normal_force_N"]) is not None]
    best = None
    if args.target:
        best = cheapest(rows, key, args.target)
        for r in rows:
            value = r.get(key)
            r["meets_target"] = value is not None and math.isfinite(value) and value <= args.target
            r["cheapest"] = r is best
    basis, reference_line = accuracy_text(scene, runs, done, rows)
    if scene.closed_form:
        error_columns = error_columns + [("hertz_pressure_l2_error", "p L2 error against Hertz")]
    reference_row = None
    if reference is not None:
        choice = runs[0]
        reference_row = {"index": "ref", **choice._asdict(), "global_refinements": scene.refinements + choice.refinement,
                         "outcome": "converged", **reference,
                         "estimates": {c: e[0] for c, e in estimates.items()}}
        if scene.closed_form:
            reference_row["hertz_pressure_l2_error"] = closed_form_error(scene, reference)

    columns = ["index", "pair", "algorithm", "stopping", "cell_shape", "refinement", "global_refinements", "rn_factor", "rt_factor",
               "outcome", "exit_code", "cells", "dofs", "load_steps", "newton_iterations", "failed_newton_iterations",
               "wall_time_s",
               "process_time_s", "peak_memory_MiB", "normal_force_N", "tangential_force_N",
               *[c for c, _ in error_columns], "estimated_relative_error", "estimated_pressure_error",
               *(["reference_estimated_error"] if estimates else []),
               *(["meets_target", "cheapest"] if args.target else [])]
    csv_path, png_path, md_path = (tool_cli.destination(args, args.name + suffix) for suffix in (".csv", ".png", ".md"))
    robustness_map.write_csv(rows, csv_path, columns)
    plot(rows, key, os.path.basename(args.scene), args.target, best, png_path,
         estimates[key][0] if estimates else None)
    show_factors = any(r["rn_factor"] != 1 or r["rt_factor"] != 1 for r in rows)
    show_stopping = len({r["stopping"] for r in rows}) > 1 or any(r["stopping"] != "fixed" for r in rows)
    show_cells = len({r["cell_shape"] for r in rows}) > 1
    robustness_map.write_section(md_path, BEGIN, END, markdown(
        rows, error_columns, key, args.target, best, scene, [reference_line] + notes if reference_line else [],
        basis, regenerating_command(args), os.path.basename(png_path), show_factors, show_stopping, show_cells,
        reference_row))

    for r in rows:
        measured = ", ".join(f"{title} {percent(r.get(c))}" for c, title in error_columns)
        print(f"#{r['index']} {r['label']}: {r['outcome']}" + (
            f", {r['dofs']} DoFs, {r['newton_iterations']} Newton, {r['wall_time_s']:.3g} s, "
            f"{r['peak_memory_MiB']:.4g} MiB, {measured}, estimate {percent(r['estimated_relative_error'])}"
            if r["outcome"] == "converged" else ""))
    for line in ([reference_line] + notes if reference_line else []):
        print(line.replace("**", "").replace("`", ""))
    if args.target:
        print(target_sentence(best, key, args.target, rows))
    print(f"wrote {md_path}, {os.path.basename(csv_path)} and {os.path.basename(png_path)}")
    return 1 if any(ran["outcome"] != "converged" for ran, _, _ in done.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
