#!/usr/bin/python3
"""The axisymmetric model (Geometry/Axisymmetric = true): x is the radius r,
the hoop strain u_r/r and the weight 2 pi r enter every integral.

1. A solid cylinder (radius R = 100 mm) pressed by a uniform pressure p on a
   frictionless rigid plane has the exact solution sigma_yy = -p,
   u_r = nu p r / E (in plane strain it would be nu (1 + nu) p r / E), which
   every pair represents exactly: the contact pressure equals p at every node,
   the normal force is p pi R^2 (a total, not per unit thickness) and the
   radial slip of each node is nu p r / E, all to solver tolerance; with
   hanging nodes on the contact surface, Q1 and Q2, both contact quadratures
   where allowed, and on 2 ranks.
2. Hertz, a ball on a rigid plane (prm/hertz_axisymmetric.prm), Q1/P1 on
   three nested meshes: the contact radius a within h + 1 % of the 3D closed
   form a = (3PR/(4E*))^(1/3) (a is the midpoint between the last loaded and
   the first unloaded node, and the node just outside the exact edge carries
   pressure through the linear multiplier: one cell), the peak pressure within
   the mesh error of p0 = 3P/(2 pi a^2), and both errors shrinking under
   refinement. The mesh
   error of a run on the mesh h is estimated from the next finer one,
   e(h) = 2 |X(h) - X(h/2)| (first-order convergence, seen below), and on the
   finest mesh as half that of the one before.
3. The same ball in 3D (the quarter model of the half ball, two nested meshes
   with the contact mesh sizes of the first two axisymmetric ones): normal
   force for the same approach, peak pressure and contact radius equal to the
   axisymmetric ones within the sum of both runs' mesh errors.
4. Q2/P1 (Gauss contact quadrature) on the ball: p0 within its mesh error.
5. What the model refuses, with a message: Dimension 3, a mesh reaching x < 0,
   F-bar, and the Gauss-Lobatto quadrature with a quadratic pair (the nodal
   weight of a node on the axis vanishes)."""
import glob
import math
import os
import sys
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
E, nu = 200000.0, 0.3
E_star = E / (1 - nu * nu)

# --- 1. the solid cylinder --------------------------------------------------
pressure, R_cylinder = 100.0, 100.0
AXISYMMETRIC_BLOCK = """
subsection Geometry
  set Axisymmetric = true
  subsection block
    set Left side = 0
  end
end
"""
cases = [("Q1/P1", "Gauss-Lobatto", 0, 1), ("Q1/P1", "Gauss", 0, 1), ("Q1/P1", "Gauss-Lobatto", 1, 1),
         ("Q2/P2", "Gauss", 0, 1), ("Q2/P1", "Gauss", 1, 1), ("Q1/P1", "Gauss-Lobatto", 1, 2)]
for pair, quadrature, local, ranks in cases:
    # local = 1: the cells within 30 mm of the rim's foot refined once more, so
    # hanging nodes run across the contact surface; the axis x = 0 (id 0) is
    # held in x by the scene's Dirichlet condition and by the axis condition
    text = sltest.scene(
        "pressed_block", DIM=2, MU=0, SLIDE=0, NU=nu, QUADRATURE=quadrature,
        SUBDIVISIONS="2, 1", REFINEMENTS=3, TANGENTIAL_ID=0, COMPONENTS="x",
        SLIDE_EXPRESSION="0; 0", VARIABLES="x,y,t", PRESSURE=pressure, PAIR=pair, LOCAL=local,
        CENTER="100, 0", RADIUS=30, TRACTION_EXPRESSION="0; -p*t", STEPS=1, VTU="true")
    text += AXISYMMETRIC_BLOCK
    name = f"cylinder {pair} {quadrature}" + (" locally refined" if local else "") + \
        (f" on {ranks} ranks" if ranks > 1 else "")
    out = f"{workdir}/cylinder-{pair.replace('/', '')}-{quadrature}-{local}-{ranks}"
    sltest.run(executable, text, out, ranks=ranks)
    profile = sltest.last_profile(out + "/output")
    error = max(abs(row["contact_pressure_MPa"] - pressure) for row in profile) / pressure
    check(error < 1e-8, f"{name}: {len(profile)} nodes, max |p - {pressure}| / {pressure} = {error:.2e}")
    force = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
    expected = pressure * math.pi * R_cylinder ** 2
    check(abs(force - expected) < 1e-8 * expected,
          f"{name}: normal force {force:.4f} N = p pi R^2 = {expected:.4f} N "
          f"(relative error {abs(force - expected) / expected:.1e})")
    radial = nu * pressure * R_cylinder / E
    slip_error = max(abs(row["slip_increment_x_mm"] - nu * pressure * row["x_mm"] / E) for row in profile)
    # the stress of the VTU: sigma_rr = sigma_ry = 0, sigma_yy = -p, the hoop stress 0
    for path in sorted(glob.glob(out + "/output/solution_00001*.vtu")):
        reader = vtkXMLUnstructuredGridReader()
        reader.SetFileName(path)
        reader.Update()
        data = reader.GetOutput().GetPointData()
        stress = vtk_to_numpy(data.GetArray("stress_MPa"))
        hoop = vtk_to_numpy(data.GetArray("hoop_stress_MPa"))
        expected_stress = np.zeros(9)  # the 2 x 2 tensor in the 3 x 3 of VTK
        expected_stress[4] = -pressure
        stress_error = max(np.abs(stress - expected_stress).max(), np.abs(hoop).max()) / pressure
        check(stress_error < 1e-8, f"{name}: {os.path.basename(path)}: stress (0, 0; 0, -p) and hoop "
              f"stress 0 in every cell, max error {stress_error:.1e} p")
    check(slip_error < 1e-8 * radial,
          f"{name}: radial slip nu p r / E at every node, max error {slip_error:.1e} mm "
          f"(rim {radial:.2e} mm; plane strain would give {(1 + nu) * radial:.2e})")

# --- 2. and 3. Hertz, axisymmetric and 3D -------------------------------------
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "hertz_axisymmetric.prm")) as f:
    axisymmetric_ball = f.read()


def measure(outdir, three_d, R=100.0):
    """Normal force P (of the whole ball), contact radius a (midpoint between the last
    loaded and the first unloaded node on a radius), contact mesh size h, peak pressure."""
    P = sltest.read_csv(outdir + "/statistics.csv")[-1]["normal_force_N"] * (4 if three_d else 1)
    profile = sltest.last_profile(outdir)
    if three_d:  # the nodes on the symmetry plane y = 0
        profile = [row for row in profile if abs(row["y_mm"]) < 1e-9]
    points = sorted((row["x_mm"], row["contact_pressure_MPa"]) for row in profile)
    last = max(i for i, (r, p) in enumerate(points) if p > 0)
    a = 0.5 * (points[last][0] + points[last + 1][0])
    h = points[last + 1][0] - points[last][0]
    p0 = max(p for r, p in points)
    return {"P": P, "a": a, "h": h, "p0": p0,
            "a_hertz": (3 * P * R / (4 * E_star)) ** (1 / 3),
            "p0_hertz": 3 * P / (2 * math.pi * (3 * P * R / (4 * E_star)) ** (2 / 3))}


def run_ball(text, name):
    out = f"{workdir}/{name}"
    sltest.run(executable, text + sltest.QUIET_OUTPUT, out)
    return measure(out + "/output", "Dimension = 3" in text)


def with_mesh(text, global_refinements, local_refinements, extra=""):
    text = text.replace("set Global refinements      = 3",
                        f"set Global refinements      = {global_refinements}")
    text = text.replace("set Local refinements       = 4",
                        f"set Local refinements       = {local_refinements}")
    return text.replace("set Local refinement radius = 20", "set Local refinement radius = 30") + extra


def mesh_errors(runs, quantity):
    """e(h) = 2 |X(h) - X(h/2)| on each mesh but the finest, half the previous one there."""
    errors = [2 * abs(coarse[quantity] - fine[quantity]) for coarse, fine in zip(runs, runs[1:])]
    return errors + [errors[-1] / 2]


axi = [run_ball(with_mesh(axisymmetric_ball, 2, local), f"axisymmetric-{local}") for local in (3, 4, 5)]
for quantity in ("p0", "P"):
    for run, error in zip(axi, mesh_errors(axi, quantity)):
        run["e_" + quantity] = error
for run in axi:
    print(f"axisymmetric h = {run['h']:.3f} mm: P = {run['P']:.0f} N, a = {run['a']:.3f} mm "
          f"(Hertz {run['a_hertz']:.3f}), p0 = {run['p0']:.1f} MPa (Hertz {run['p0_hertz']:.1f}, "
          f"mesh error {run['e_p0']:.1f})")
    check(abs(run["a"] - run["a_hertz"]) <= run["h"] + 0.01 * run["a_hertz"],
          f"axisymmetric h = {run['h']:.3f}: |a - a_H| = {abs(run['a'] - run['a_hertz']):.3f} mm "
          "<= h + 1% a_H (1%: the finite ball against the half-space of the closed form)")
    check(abs(run["p0"] - run["p0_hertz"]) <= run["e_p0"] + 0.01 * run["p0_hertz"],
          f"axisymmetric h = {run['h']:.3f}: |p0 - p0_H| = {abs(run['p0'] - run['p0_hertz']):.1f} MPa "
          f"<= mesh error {run['e_p0']:.1f} + 1% p0_H")
for coarse, fine in zip(axi, axi[1:]):
    check(abs(fine["a"] - fine["a_hertz"]) < abs(coarse["a"] - coarse["a_hertz"]),
          f"axisymmetric contact radius error shrinks: {abs(coarse['a'] - coarse['a_hertz']):.3f} "
          f"(h = {coarse['h']:.3f}) -> {abs(fine['a'] - fine['a_hertz']):.3f} mm (h = {fine['h']:.3f})")
    error_coarse = abs(coarse["p0"] - coarse["p0_hertz"]) / coarse["p0_hertz"]
    error_fine = abs(fine["p0"] - fine["p0_hertz"]) / fine["p0_hertz"]
    check(error_fine < 0.75 * error_coarse,
          f"axisymmetric peak pressure error shrinks (first order): {error_coarse:.2%} "
          f"(h = {coarse['h']:.3f}) -> {error_fine:.2%} (h = {fine['h']:.3f})")

with open(os.path.join(os.path.dirname(__file__), "..", "prm", "hertz_sphere.prm")) as f:
    sphere = f.read()
QUARTER = sltest.nested_set("Geometry/half ball/Symmetry planes", "true") + sltest.SYMMETRY_PLANES[3]
sphere = sphere.replace("set Global refinements      = 2", "set Global refinements      = 3")
sphere = sphere.replace("set Local refinements       = 3", "set Local refinements       = 4")
three_d = [run_ball(with_mesh(sphere, 2, local, QUARTER), f"three-d-{local}") for local in (3, 4)]
for quantity in ("p0", "P"):
    for run, error in zip(three_d, mesh_errors(three_d, quantity)):
        run["e_" + quantity] = error
for run_3d, run_axi in zip(three_d, axi):
    label = f"h = {run_3d['h']:.3f} (3D) / {run_axi['h']:.3f} (axisymmetric)"
    check(abs(run_3d["h"] - run_axi["h"]) < 0.01 * run_3d["h"], f"{label}: comparable contact meshes")
    for quantity, unit in (("P", "N"), ("p0", "MPa")):
        bound = run_3d["e_" + quantity] + run_axi["e_" + quantity]
        difference = abs(run_3d[quantity] - run_axi[quantity])
        check(difference <= bound,
              f"{label}: {quantity} 3D {run_3d[quantity]:.1f} against axisymmetric "
              f"{run_axi[quantity]:.1f} {unit}: difference {difference:.1f} <= the two mesh errors "
              f"{bound:.1f}")
    check(abs(run_3d["a"] - run_axi["a"]) <= 0.5 * (run_3d["h"] + run_axi["h"]),
          f"{label}: contact radius 3D {run_3d['a']:.3f} against axisymmetric {run_axi['a']:.3f} mm, "
          "within h (each within one cell of its contact edge)")

# --- 4. Q2/P1 ------------------------------------------------------------------
Q2 = "\nsubsection Contact\n  set Finite element pair = Q2/P1\n  set Contact quadrature = Gauss\nend\n"
quadratic = [run_ball(with_mesh(axisymmetric_ball, 2, local, Q2), f"q2-{local}") for local in (4, 5)]
e_quadratic = mesh_errors(quadratic, "p0")
for run, error in zip(quadratic, e_quadratic):
    check(abs(run["p0"] - run["p0_hertz"]) <= error + 0.01 * run["p0_hertz"],
          f"Q2/P1 h = {run['h']:.3f}: p0 = {run['p0']:.1f} MPa against Hertz {run['p0_hertz']:.1f}: "
          f"|error| {abs(run['p0'] - run['p0_hertz']):.1f} <= mesh error {error:.1f} + 1% p0_H")

# --- 5. refused input ------------------------------------------------------------
refused = [
    ("Dimension 3", sphere + "\nsubsection Geometry\n  set Axisymmetric = true\nend\n",
     ["Geometry/Axisymmetric", "Dimension = 2"]),
    ("a mesh reaching x < 0",
     axisymmetric_ball.replace("set Symmetry planes         = true", "set Symmetry planes         = false"),
     ["Geometry/Axisymmetric", "x >= 0"]),
    ("F-bar", axisymmetric_ball + "\nsubsection Material\n  set Volumetric formulation = F-bar\nend\n",
     ["Material/Volumetric formulation", "displacement"]),
    ("Gauss-Lobatto with Q2/P2",
     axisymmetric_ball + "\nsubsection Contact\n  set Finite element pair = Q2/P2\nend\n",
     ["Gauss-Lobatto", "Use Contact quadrature = Gauss"]),
]
for index, (name, text, words) in enumerate(refused):
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, f"{workdir}/refused-{index}",
                           expect_success=False)
    missing = [w for w in words if w not in log]
    check(code != 0 and not missing,
          f"refused: {name}: exit code {code}, the message names {words}" +
          (f" (missing {missing})" if missing else ""))
    if missing:
        print(log[-2000:])
check.finish()
