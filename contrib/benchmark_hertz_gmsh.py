#!/usr/bin/python3
"""Hertz contact pressure on unstructured hexahedral or tetrahedral meshes.

Usage: contrib/benchmark_hertz_gmsh.py --executable build/stabilized_lagrangian
                                       [--baseline OLD_EXECUTABLE] [--workdir DIR]
                                       [--jobs N] [--size-factors 1,0.7,0.5]
                                       [--refinements 0] [--cells hexahedra|tetrahedra]
                                       [--pair PAIR] [--doc [FILE]]

Runs prm/hertz_sphere_gmsh.prm (a quarter of a ball, R = 50 mm, pressed by
P = 20 kN onto a rigid frictionless plane; Q1/P1) on three meshes of
prm/meshes/hertz_quarter_ball.geo, made anew by Gmsh with every size
multiplied by a factor (a variant .geo in the work directory sets
`size_factor` and includes the shipped one), with `Contact quadrature =
Gauss-Lobatto` (the default) and `Gauss`. With --baseline the same runs are
made with a second executable (e.g. a build before a fix) and shown beside.
With --refinements the meshes are also refined uniformly (e.g. `--size-factors 2
--refinements 0,1,2`): nested meshes whose new vertices on the ball lie on the
sphere (`Spherical boundaries` of the scene), so the observed order is that of
the discretisation, not of the mesh generator's choices. With --cells
tetrahedra the .geo's tetrahedra are kept (no subdivision) and the pair is
P1/P1 unless --pair.

Per run: DoFs, the normal force P (four times the quarter's), and the errors
of the nodal contact pressure against Hertz's closed form with the run's own
force (a = (3PR/(4E*))^(1/3), p0 = 3P/(2 pi a^2), p(r) = p0 sqrt(1 - r^2/a^2),
E* = E/(1 - nu^2)):

  L2     relative L2 error over the contact surface within r <= 1.5 a: the
         nodal pressures interpolated linearly on a Delaunay triangulation of
         the nodes (projected on z = 0), integrated against the exact curve
         with 36 sub-triangles per triangle (the square-root edge of the
         exact curve is integrated accurately). An area-weighted measure: on
         a graded unstructured mesh the nodal root mean square of
         contrib/hertz_errors.py weighs the small cells more; it is kept in
         the CSV as `nodal_rms_error`.
  p(0)   signed relative error of the pressure at the south pole (the
         centre of the contact) against p0.
  max p  signed relative error of the largest nodal pressure against p0.
  rate   observed order of the L2 error in h, with h ~ DoFs^(-1/3).
  interp the L2 measure applied to the exact pressure at the same nodes: the
         error of the linear interpolation of the square-root profile alone,
         the floor of the L2 measure on that mesh (it decreases like h: the
         profile's edge).

The per-run rows go to WORKDIR/hertz_gmsh_hexahedra.csv; with --doc the
Markdown table goes to doc/hertz_gmsh_hexahedra.md (or the FILE given)."""
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
import run_output  # noqa: E402
from hertz_errors import hertz_errors  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
E, NU, R = 200000.0, 0.3, 50.0
E_STAR = E / (1 - NU * NU)
QUADRATURES = ("Gauss-Lobatto", "Gauss")

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--executable", required=True, help="the stabilized_lagrangian to measure")
parser.add_argument("--baseline", help="a second executable (e.g. before a fix), run on the same meshes")
parser.add_argument("--label", default="", help="label of --executable in the table (default: its path)")
parser.add_argument("--baseline-label", default="before the fix", help="label of --baseline in the table")
parser.add_argument("--workdir", default="/tmp/benchmark_hertz_gmsh")
parser.add_argument("--jobs", type=int, default=1, help="runs at a time (each on one MPI rank)")
parser.add_argument("--size-factors", default="1,0.7,0.5",
                    help="mesh size factors, coarse to fine (1: the shipped mesh)")
parser.add_argument("--refinements", default="0",
                    help="uniform refinements of each mesh, coarse to fine (nested meshes)")
parser.add_argument("--cells", choices=("hexahedra", "tetrahedra"), default="hexahedra",
                    help="hexahedra: Gmsh's tetrahedra each subdivided into four hexahedra (the shipped .geo); "
                         "tetrahedra: the tetrahedra themselves (default: %(default)s)")
parser.add_argument("--pair", help="the FE pair (default: Q1/P1 on hexahedra, P1/P1 on tetrahedra)")
parser.add_argument("--doc", nargs="?", const="",
                    help="write the Markdown table (default doc/hertz_gmsh_<cells>.md)")
args = parser.parse_args()
args.pair = args.pair or ("Q1/P1" if args.cells == "hexahedra" else "P1/P1")
if args.doc == "":
    args.doc = os.path.join(ROOT, "doc", f"hertz_gmsh_{args.cells}.md")
try:
    meshes = [(float(f), int(n)) for f in args.size_factors.split(",") for n in args.refinements.split(",")]
except ValueError:
    parser.error("--size-factors takes numbers and --refinements integers, separated by commas")
if any(f <= 0 or n < 0 for f, n in meshes):
    parser.error("size factors must be > 0 and refinements >= 0")
builds = [(args.label or args.executable, os.path.abspath(args.executable))]
if args.baseline:
    builds.insert(0, (args.baseline_label, os.path.abspath(args.baseline)))
os.makedirs(args.workdir, exist_ok=True)
workdir = os.path.abspath(args.workdir)


def read_csv(path):
    return run_output.read_csv(path)


def mesh_file(factor):
    """A .geo that sets the size factor and includes the shipped geometry."""
    os.makedirs(os.path.join(workdir, "meshes"), exist_ok=True)
    path = os.path.join(workdir, "meshes", f"hertz_quarter_ball_{args.cells}_{factor:g}.geo")
    with open(path, "w") as f:
        f.write(f"size_factor = {factor!r};\n"
                f"Include \"{os.path.join(ROOT, 'prm', 'meshes', 'hertz_quarter_ball.geo')}\";\n")
        if args.cells == "tetrahedra":
            f.write("Mesh.SubdivisionAlgorithm = 0;\n")
    return path


def scene(mesh, quadrature):
    factor, refinements = mesh
    with open(os.path.join(ROOT, "prm", "hertz_sphere_gmsh.prm")) as f:
        text = f.read()
    return text + f"""
subsection Geometry
  subsection gmsh
    set Mesh file = {mesh_file(factor)}
    set Global refinements = {refinements}
  end
end
subsection Contact
  set Contact quadrature = {quadrature}
  set Finite element pair = {args.pair}
end
subsection Output
  set Output directory = output
  set Write vtu = false
end
"""


# --- the L2 error on a Delaunay triangulation of the contact nodes ----------

def delaunay(points):
    """Triangles (index triples) of the Delaunay triangulation of 2D points
    (Bowyer-Watson; a few thousand points at most here)."""
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    cx, cy = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-12)
    pts = list(points) + [(cx - 20 * span, cy - 20 * span), (cx + 20 * span, cy - 20 * span),
                          (cx, cy + 20 * span)]
    n = len(points)

    def circumcircle(t):
        (ax, ay), (bx, by), (qx, qy) = pts[t[0]], pts[t[1]], pts[t[2]]
        d = 2 * (ax * (by - qy) + bx * (qy - ay) + qx * (ay - by))
        ux = ((ax * ax + ay * ay) * (by - qy) + (bx * bx + by * by) * (qy - ay) + (qx * qx + qy * qy) * (ay - by)) / d
        uy = ((ax * ax + ay * ay) * (qx - bx) + (bx * bx + by * by) * (ax - qx) + (qx * qx + qy * qy) * (bx - ax)) / d
        return ux, uy, (ax - ux) ** 2 + (ay - uy) ** 2

    triangles = {(n, n + 1, n + 2): circumcircle((n, n + 1, n + 2))}
    for i in range(n):
        px, py = pts[i]
        bad = [t for t, (ux, uy, r2) in triangles.items() if (px - ux) ** 2 + (py - uy) ** 2 < r2 * (1 + 1e-12)]
        edges = {}
        for t in bad:
            for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                key = tuple(sorted(e))
                edges[key] = edges.get(key, 0) + 1
            del triangles[t]
        for (a, b), count in edges.items():
            if count == 1:
                t = (a, b, i)
                (ax, ay), (bx, by) = pts[a], pts[b]
                if abs((bx - ax) * (py - ay) - (by - ay) * (px - ax)) > 1e-14 * span * span:
                    triangles[t] = circumcircle(t)
    return [t for t in triangles if max(t) < n]


def l2_error(profile, a_h, p0_h, subdivisions=6):
    """Relative L2 error of the linearly interpolated nodal pressure within 1.5 a."""
    nodes = [(row["x_mm"], row["y_mm"], row["contact_pressure_MPa"]) for row in profile
             if math.hypot(row["x_mm"], row["y_mm"]) <= 1.5 * a_h]
    points = [(x, y) for x, y, _ in nodes]

    def exact(x, y):
        return p0_h * math.sqrt(max(0.0, 1 - (x * x + y * y) / (a_h * a_h)))

    num = den = 0.0
    m = subdivisions
    for i, j, k in delaunay(points):
        (x0, y0, p0), (x1, y1, p1), (x2, y2, p2) = nodes[i], nodes[j], nodes[k]
        area = 0.5 * abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0))
        w = area / (m * m)
        # centroids of the m^2 sub-triangles, in barycentric coordinates
        for s in range(m):
            for t in range(m - s):
                for (bs, bt) in (((s + 1 / 3) / m, (t + 1 / 3) / m), ((s + 2 / 3) / m, (t + 2 / 3) / m)):
                    if bs + bt > 1:
                        continue
                    x = x0 + bs * (x1 - x0) + bt * (x2 - x0)
                    y = y0 + bs * (y1 - y0) + bt * (y2 - y0)
                    p = p0 + bs * (p1 - p0) + bt * (p2 - p0)
                    e = exact(x, y)
                    num += w * (p - e) ** 2
                    den += w * e * e
    return math.sqrt(num / den)


# --- the runs ---------------------------------------------------------------

def mesh_name(mesh):
    return f"{mesh[0]:g}" + (f" + {mesh[1]} ref." if mesh[1] else "")


def run(build, mesh, quadrature):
    label, executable = build
    factor, refinements = mesh
    name = f"build{[b[0] for b in builds].index(label)}-size{factor:g}-ref{refinements}-{quadrature}"
    directory = os.path.join(workdir, name)
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "input.prm"), "w") as f:
        f.write(scene(mesh, quadrature))
    start = time.time()
    result = subprocess.run([executable, "input.prm"], cwd=directory, capture_output=True, text=True)
    elapsed = time.time() - start
    with open(os.path.join(directory, "log.txt"), "w") as f:
        f.write(result.stdout + result.stderr)
    if result.returncode != 0:
        print(f"  {label} size {mesh_name(mesh)} {quadrature}: exit code {result.returncode} "
              f"(see {directory}/log.txt)", flush=True)
        return None
    out = os.path.join(directory, "output")
    summary = read_csv(os.path.join(out, "run_summary.csv"))[0]
    statistics = read_csv(os.path.join(out, "statistics.csv"))[-1]
    P = 4 * statistics["normal_force_N"]  # the quarter carries P/4
    profile = read_csv(os.path.join(out, sorted(p for p in os.listdir(out) if p.startswith("profile-"))[-1]))
    a_h = (3 * P * R / (4 * E_STAR)) ** (1 / 3)
    p0_h = 3 * P / (2 * math.pi * a_h ** 2)
    pole = min(profile, key=lambda row: math.hypot(row["x_mm"], row["y_mm"]))
    row = {"build": label, "size_factor": factor, "refinements": refinements, "quadrature": quadrature,
           "dofs": int(summary["displacement_dofs"] + summary["multiplier_dofs"]),
           "newton_iterations": int(summary["newton_iterations"]), "wall_time_s": elapsed,
           "normal_force_N": P, "a_hertz_mm": a_h, "p0_hertz_MPa": p0_h,
           "l2_error": l2_error(profile, a_h, p0_h),
           "pole_error": pole["contact_pressure_MPa"] / p0_h - 1,
           "max_error": max(r["contact_pressure_MPa"] for r in profile) / p0_h - 1,
           "nodal_rms_error": hertz_errors(3, P, profile, E=E, nu=NU, R=R)["l2_error"],
           "interpolation_error": l2_error(
               [dict(r, contact_pressure_MPa=p0_h * math.sqrt(max(0.0, 1 - (r["x_mm"] ** 2 + r["y_mm"] ** 2) / a_h ** 2)))
                for r in profile], a_h, p0_h)}
    print(f"  {label} size {mesh_name(mesh)} {quadrature:13s}: {row['dofs']:7d} DoFs, {row['newton_iterations']} Newton, "
          f"{elapsed:.1f} s, P = {P:.0f} N, L2 {row['l2_error']:.2%}, p(0) {row['pole_error']:+.2%}, "
          f"max p {row['max_error']:+.2%}", flush=True)
    return row


cases = [(b, m, q) for b in builds for m in meshes for q in QUADRATURES]
table = os.path.join(workdir, f"hertz_gmsh_{args.cells}.csv")
for factor in {m[0] for m in meshes}:
    mesh_file(factor)  # written before the runs that read it start
start = time.time()
with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
    # the finest meshes first, so that the runs at a time end together
    futures = {c: pool.submit(run, *c) for c in sorted(cases, key=lambda c: c[1][0] / 2 ** c[1][1])}
    results = {c: futures[c].result() for c in cases}
total = time.time() - start
rows = [r for r in (results[c] for c in cases) if r]
fields = list(rows[0].keys()) if rows else []
with open(table, "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
print(f"{len(rows)} of {len(cases)} runs in {total:.0f} s; rows in {table}")


def rate(previous, row):
    if not previous or not row:
        return ""
    return f"{-3 * math.log(row['l2_error'] / previous['l2_error']) / math.log(row['dofs'] / previous['dofs']):.2f}"


def cells(row, previous):
    if not row:
        return ["failed", "", "", ""]
    return [f"{row['l2_error']:.3f}", rate(previous, row), f"{row['pole_error']:+.1%}", f"{row['max_error']:+.1%}"]


if args.doc:
    command = "contrib/benchmark_hertz_gmsh.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    cells_text = ("tetrahedra each subdivided into four hexahedra" if args.cells == "hexahedra" else
                  "tetrahedra, the contact faces triangles")
    shape = "hexahedral" if args.cells == "hexahedra" else "tetrahedral"
    lines = [f"# Hertz contact pressure on unstructured {shape} meshes", "",
             "The scene of prm/hertz_sphere_gmsh.prm: a ball (R = 50 mm, E = 200000 MPa, nu = 0.3) pressed "
             "by P = 20 kN onto a rigid frictionless plane, a quarter model meshed by Gmsh "
             f"(prm/meshes/hertz_quarter_ball.geo: {cells_text}, a size "
             "field graded toward the contact point" + ("; the contact faces are general quadrilaterals, not "
             "parallelograms" if args.cells == "hexahedra" else "") + f"), {args.pair}, the whole load in one step. The meshes are made anew with every size "
             "multiplied by the size factor, then refined uniformly `ref.` times (new vertices on the "
             "sphere: nested meshes). Errors against the closed form of Hertz with the run's own "
             "normal force (a ~ 1.5 mm, p0 ~ 4.2 GPa):", "",
             "- L2: relative L2 error of the nodal pressure interpolated linearly over the contact surface "
             "within r <= 1.5 a; rate: its order in h ~ DoFs^(-1/3);",
             "- interp: the same measure for the exact pressure at the same nodes, i.e. the error of the "
             "linear interpolation of the square-root profile alone: the floor of the L2 measure on that "
             "mesh, which decreases like h (the profile's edge);",
             "  with nested meshes h halves from one to the next and the rate is log2 of the ratio;",
             "- p(0): signed error of the pressure at the centre of the contact against p0;",
             "- max p: signed error of the largest nodal pressure against p0.", "",
             "Both contact quadratures are those of doc/formulation.md (`Contact quadrature`: "
             "Gauss-Lobatto, the default, and Gauss).", ""]
    for label, executable in builds:
        lines += [f"## {label}", "",
                  "| mesh | DoFs | interp | Gauss-Lobatto: L2 | rate | p(0) | max p "
                  "| Gauss: L2 | rate | p(0) | max p |",
                  "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        previous = {q: None for q in QUADRATURES}
        for mesh in meshes:
            gl, g = (results[((label, executable), mesh, q)] for q in QUADRATURES)
            dofs = (gl or g or {}).get("dofs", "")
            interp = f"{(gl or g)['interpolation_error']:.3f}" if (gl or g) else ""
            lines.append(f"| {mesh_name(mesh)} | {dofs} | {interp} | " + " | ".join(cells(gl, previous[QUADRATURES[0]]) +
                                                                 cells(g, previous[QUADRATURES[1]])) + " |")
            previous = {QUADRATURES[0]: gl, QUADRATURES[1]: g}
        times = [r["wall_time_s"] for r in rows if r["build"] == label]
        newton = [r["newton_iterations"] for r in rows if r["build"] == label]
        lines += ["", "Normal force P (four times the quarter's): "
                  + ", ".join(sorted({f"{r['normal_force_N']:.0f} N" for r in rows if r['build'] == label}))
                  + f"; Newton iterations {min(newton, default=0)}-{max(newton, default=0)}; "
                  f"wall time per run {min(times, default=0):.0f}-{max(times, default=0):.0f} s.", ""]
    lines += [f"Generated by `{command}` ({len(rows)} runs, {args.jobs} at a time, one MPI rank each, "
              f"2-core machine: {total / 60:.1f} min).", ""]
    with open(args.doc, "w") as f:
        f.write("\n".join(lines))
    print(f"wrote {args.doc}")
