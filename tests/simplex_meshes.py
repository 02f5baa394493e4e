#!/usr/bin/python3
"""Triangle and tetrahedron meshes (the built-in block with `Cell shape = simplex`: every
quadrilateral split into 8 triangles, every hexahedron into 24 tetrahedra).

A block pressed uniformly onto a frictionless rigid plane: the contact pressure is the
applied pressure at every node of the contact surface to 1e-10 and the normal force is
p x area, for every inf-sup stable simplex pair (P1/P1, P2/P1, P2/P2), both contact
quadratures (Gauss-Lobatto only for P1/P1 in 3D: the quadratic nodal weights of a
triangle vanish at its vertices), on 1 and 2 MPI ranks, and with hanging nodes across the
contact surface in 2D. The exact solution is linear, so every pair represents it. P1/P2
violates the inf-sup condition (singular where contact is active) and is left out.

Hertz's cylinder on triangles (P1/P1, three nested meshes): the L2 error of the pressure, the
peak pressure error fall, the first at order 0.5 to 1.5 in h over two refinements; the half-width (that of the last node
in contact) is within one contact cell of Hertz's.

The inf-sup test (`--inf-sup 4`) on triangles: beta_h of P1/P1, P2/P1 and P2/P2 does not
fall under refinement, that of P1/P2 is zero.

Pressed and then slid far beyond the onset of sliding (nu = 0), every contact node slips
and F_t = mu F_n on triangles and tetrahedra.

What simplex meshes cannot do is refused with a message naming the entry: a Q pair on a
simplex mesh and a P pair on a hexahedral one, adaptive refinement cycles, local
refinement of tetrahedra, a quadratic pair on a locally refined simplex mesh on 2 ranks,
Gauss-Lobatto contact points with P2 on tetrahedra."""
import csv
import os
import subprocess
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
from hertz_errors import hertz_errors, hertz_scene  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
pressure = 100.0


def block(dim, pair, quadrature="Gauss-Lobatto", local=0, mu=0.0, slide=0.0, nu=0.3,
          cell_shape="simplex", refinements=None):
    """The pressed block of tests/scenes/pressed_block.prm; slide > 0: the top face is
    pushed sideways by `slide` in the second half of the load path (x held on the top)."""
    variables = "x,y,t" if dim == 2 else "x,y,z,t"
    sliding = slide > 0
    slide_x = "if(t < 0.5, 0, d*(t - 0.5)/0.5)"
    return sltest.scene(
        "pressed_block", DIM=dim, MU=mu, SLIDE=slide, NU=nu, QUADRATURE=quadrature,
        SUBDIVISIONS="2, 1" if dim == 2 else "2, 1, 1",
        REFINEMENTS=refinements if refinements is not None else (2 if dim == 2 else 1),
        TANGENTIAL_ID=3 if sliding else 0,
        COMPONENTS=("x" if dim == 2 else "x, y") if sliding else "x",
        SLIDE_EXPRESSION=(f"{slide_x}; 0" if dim == 2 else f"{slide_x}; 0; 0") if sliding else
        ("0; 0" if dim == 2 else "0; 0; 0"),
        VARIABLES=variables, PRESSURE=pressure, PAIR=pair, LOCAL=local,
        CENTER="-50, 0" if dim == 2 else "-50, 0, 0", RADIUS=30,
        TRACTION_EXPRESSION=("0; -p*min(2*t, 1)" if dim == 2 else "0; 0; -p*min(2*t, 1)") if sliding
        else ("0; -p*t" if dim == 2 else "0; 0; -p*t"),
        STEPS=4 if sliding else 2, VTU="false", CELL_SHAPE=cell_shape)


# --- uniform pressure --------------------------------------------------------------------
cases = []
for dim in (2, 3):
    for pair in ("P1/P1", "P2/P1", "P2/P2"):
        for quadrature in ("Gauss-Lobatto", "Gauss"):
            if dim == 3 and quadrature == "Gauss-Lobatto" and pair != "P1/P1":
                continue
            for ranks in (1, 2):
                cases.append((dim, pair, quadrature, 0, ranks))
# hanging nodes across the contact surface: the cells within 30 mm of a corner refined once more
cases += [(2, "P1/P1", "Gauss-Lobatto", 1, 2), (2, "P2/P2", "Gauss", 1, 1), (2, "P2/P1", "Gauss-Lobatto", 1, 1)]
for dim, pair, quadrature, local, ranks in cases:
    name = f"{dim}D {pair} {quadrature}, {ranks} rank(s)" + (", locally refined" if local else "")
    out = f"{workdir}/pressure-{dim}d-{pair.replace('/', '')}-{quadrature}-{local}-{ranks}"
    code, log = sltest.run(executable, block(dim, pair, quadrature, local), out, ranks=ranks,
                           expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-1500:])
        continue
    values = [row["contact_pressure_MPa"] for row in sltest.last_profile(out + "/output")]
    error = max(abs(v - pressure) for v in values) / pressure
    check(error < 1e-10, f"{name}: {len(values)} nodes, max |p - {pressure}| / {pressure} = {error:.1e}")
    stats = sltest.read_csv(out + "/output/statistics.csv")[-1]
    area = 100.0 if dim == 2 else 100.0 * 50.0
    force_error = abs(stats["normal_force_N"] - pressure * area) / (pressure * area)
    check(force_error < 1e-10, f"{name}: F_n = {stats['normal_force_N']:.6f} = p x area "
          f"(relative error {force_error:.1e})")

# --- sliding ------------------------------------------------------------------------------
mu = 0.1
for dim in (2, 3):
    onset = mu * pressure * 50.0 / 100000.0  # elastic shear G d / H = mu p, G = E/2 (nu = 0)
    out = f"{workdir}/slide-{dim}d"
    sltest.run(executable, block(dim, "P1/P1", mu=mu, slide=10 * onset, nu=0.0), out)
    stats = sltest.read_csv(out + "/output/statistics.csv")[-1]
    fn, ft = stats["normal_force_N"], stats["tangential_force_N"]
    check(stats["points_stick"] == 0 and stats["points_slip"] == stats["points_in_contact"] > 0,
          f"{dim}D slide: {int(stats['points_slip'])} points slip, {int(stats['points_stick'])} stick")
    check(abs(ft - mu * fn) < 1e-8 * mu * fn,
          f"{dim}D slide: F_t = {ft:.8f} = mu F_n = {mu * fn:.8f}")

# --- Hertz on triangles: the errors fall under refinement ---------------------------------------
# prm/hertz_cylinder.prm (frictionless half cylinder, R = 100 mm, pressed by 0.25 mm, one load
# step) with its half disc split into triangles, P1/P1, global refinements 2, 3, 4 (the contact
# mesh size 1.23, 0.61, 0.31 mm). The pressure's square-root edge limits every pair to about
# order 1 in h for the L2 error of the pressure (doc/simplex_meshes.md); the peak pressure
# falls too, the half-width is within one contact cell of Hertz's.
errors = []
for refinements in (2, 3, 4):
    text = hertz_scene(2, "P1/P1", 4, 0.25) + f"""
subsection Geometry
  subsection half ball
    set Cell shape = simplex
    set Global refinements = {refinements}
  end
end
""" + sltest.QUIET_OUTPUT
    out = f"{workdir}/hertz-{refinements}"
    sltest.run(executable, text, out)
    force = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
    errors.append(hertz_errors(2, force, sltest.last_profile(out + "/output")))
# over two levels > 0.5 (level to level 0.1 to 1.5 for Q1/P1 on the same meshes,
# doc/benchmark_hertz.md)
sltest.check_hertz_sequence(check, errors, "Hertz on triangles", 0.5)

# --- inf-sup test on triangles: the stable pairs keep beta_h, P1/P2 has beta_h = 0 ----------
def betas(pair):
    out = f"{workdir}/inf-sup-{pair.replace('/', '')}"
    os.makedirs(out, exist_ok=True)
    with open(out + "/input.prm", "w") as f:
        f.write(block(2, pair, refinements=1))
    result = subprocess.run([executable, "--inf-sup", "4", "input.prm"], cwd=out, capture_output=True, text=True)
    check(result.returncode == 0, f"{pair}: --inf-sup exit code {result.returncode}")
    with open(out + "/output/inf_sup.csv") as f:
        return [float(r["beta"]) for r in csv.DictReader(f)]


stable = []
for pair in ("P1/P1", "P2/P1", "P2/P2"):
    b = betas(pair)
    stable += b
    check(b[-1] >= b[-2] * 0.99 and min(b[-2:]) > 0.1, f"{pair} stable: beta_h = {', '.join(f'{x:.3f}' for x in b)}")
b = betas("P1/P2")
check(max(b) < 1e-6 * min(stable), f"P1/P2 unstable, beta_h = 0: max {max(b):.2e}")

# --- what simplex meshes refuse -----------------------------------------------------------
refusals = (
    ("Q pair on triangles", block(2, "Q1/P1"), 1, "Finite element pair = Q1/P1 is for quadrilaterals"),
    ("P pair on hexahedra", block(3, "P1/P1", cell_shape="hypercube"), 1,
     "Finite element pair = P1/P1 is for triangles"),
    ("adaptive cycles", block(2, "P1/P1") + "\nsubsection Adaptive refinement\n  set Cycles = 1\nend\n", 1,
     "Adaptive refinement/Cycles must be 0 on a simplex mesh"),
    ("tetrahedra locally refined", block(3, "P1/P1", local=1), 1, "Local refinements must be 0"),
    ("P2 on a locally refined mesh, 2 ranks", block(2, "P2/P1", local=1), 2, "runs on one MPI rank only"),
    ("P2 with Gauss-Lobatto on tetrahedra", block(3, "P2/P2"), 1, "Contact quadrature = Gauss-Lobatto"),
)
for name, text, ranks, message in refusals:
    code, log = sltest.run(executable, text, f"{workdir}/refused-{name.replace(' ', '_')}", ranks=ranks,
                           expect_success=False)
    check(code == 1 and message in log, f"{name}: exit {code}, refused with '{message}'")
check.finish()
