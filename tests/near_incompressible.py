#!/usr/bin/python3
"""Near incompressibility (nu = 0.4999) with `Material/Volumetric formulation = F-bar` and `mixed`.

The elastic patin of prm/patin_elastic.prm with nu = 0.4999 (pressed by 0.5 mm, then slid):
with Q1/P1 on its 32 x 16 cells the displacement formulation locks (the normal force more than
1.5 times that of Q2/P2 on the mesh refined once more), while F-bar gives the Q2/P2 force within
1 % (the issue's bound), on 1 and 2 MPI ranks (the same force to 1e-8), and the generalized
Newton reaches the nested loops' force to 1e-6. Mixed with Q2/P1 (Q2/P1disc) on the same cells
gives it within 1 % too (the same on 2 ranks to 1e-8, and with the generalized Newton to 1e-6), and mixed with P2/P1 on the triangles of
prm/patin_elastic_triangles.prm within 1 %; mixed with P1/P1 on triangles is refused with a
message naming P2. The contact patch test between two bodies (prm/contact_patch_test.prm,
nu = 0.4999, 2 ranks, Q1/P1 with F-bar and Q2/P1 with mixed) keeps its exact uniform pressure. In
3D (prm/patin_3d.prm at nu = 0.4999) the displacement formulation locks (more than 3 times F-bar's
force) and Q1 mixed equals F-bar on its box cells.

Hertz's cylinder (prm/hertz_cylinder.prm, one load step; the closed form holds for any nu) with
nu = 0.4999 and Q1/P1: the displacement formulation's pressure is off by more than 50 % (L2),
F-bar's falls under refinement of the contact zone (contact mesh size 1.23, 0.61, 0.31 mm) at
order about 1 in h, like the pressure of nu = 0.3 (the square-root edge), its peak error falls,
and its half-width is within one contact cell of Hertz's.

Cook's membrane (prm/cook_membrane.prm, nu = 0.4999, small strain): with F-bar the corner's
vertical displacement grows and converges on 4, 8, 16 cells per edge (each difference less than
0.6 times the one before), within 2 % of Q2/P1's on 16 x 16, where the displacement formulation
gives less than half of it. Q2/P1 mixed has converged from 4 cells per edge on (its values on 4,
8, 16 within 0.5 % of each other, where F-bar's move by 8 % and 2.7 %), within 2 % of F-bar's on
16 x 16."""
import os
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
import cook_membrane  # noqa: E402
from hertz_errors import hertz_errors, hertz_scene  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
NU = 0.4999


def formulation(name):
    return f"\nsubsection Material\n  set Volumetric formulation = {name}\nend\n" + sltest.QUIET_OUTPUT


# --- the patin ---------------------------------------------------------------------------
with open(os.path.join(root, "prm", "patin_elastic.prm")) as f:
    patin = f.read()
for entry in ("set Poisson's ratio = 0.3", "set Finite element pair  = Q1/P1", "set Global refinements = 4"):
    check(entry in patin, f"prm/patin_elastic.prm sets '{entry}'")
patin = patin.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {NU}")


def normal_force(name, text, ranks=1):
    out = f"{workdir}/patin-{name}"
    sltest.run(executable, text, out, ranks=ranks)
    return sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]


reference = normal_force("Q2P2", patin.replace("set Finite element pair  = Q1/P1", "set Finite element pair  = Q2/P2")
                         .replace("set Global refinements = 4", "set Global refinements = 5")
                         + formulation("displacement"))
locked = normal_force("Q1P1-displacement", patin + formulation("displacement"))
f_bar = normal_force("Q1P1-F-bar", patin + formulation("F-bar"))
f_bar_2 = normal_force("Q1P1-F-bar-2-ranks", patin + formulation("F-bar"), ranks=2)
check(locked > 1.5 * reference, f"patin, Q1/P1 displacement formulation locks: F_n = {locked:.0f} N, "
      f"{locked / reference:.2f} x Q2/P2's {reference:.0f} N")
check(abs(f_bar - reference) < 0.01 * reference, f"patin, Q1/P1 F-bar: F_n = {f_bar:.0f} N, "
      f"{(f_bar - reference) / reference:+.2%} from Q2/P2's")
check(abs(f_bar_2 - f_bar) < 1e-8 * f_bar, f"patin, Q1/P1 F-bar on 2 ranks: F_n = {f_bar_2:.4f} N")
mixed = normal_force("Q2P1-mixed", patin.replace("set Finite element pair  = Q1/P1", "set Finite element pair  = Q2/P1")
                     + formulation("mixed"))
mixed_2 = normal_force("Q2P1-mixed-2-ranks", patin.replace("set Finite element pair  = Q1/P1",
                                                           "set Finite element pair  = Q2/P1")
                       + formulation("mixed"), ranks=2)
check(abs(mixed - reference) < 0.01 * reference, f"patin, Q2/P1 mixed: F_n = {mixed:.0f} N, "
      f"{(mixed - reference) / reference:+.2%} from Q2/P2's")
check(abs(mixed_2 - mixed) < 1e-8 * mixed, f"patin, Q2/P1 mixed on 2 ranks: F_n = {mixed_2:.4f} N")
mixed_newton = normal_force("Q2P1-mixed-newton", patin.replace("set Finite element pair  = Q1/P1",
                                                               "set Finite element pair  = Q2/P1")
                            + formulation("mixed") + sltest.GENERALIZED_NEWTON)
check(abs(mixed_newton - mixed) < 1e-6 * mixed,
      f"patin, Q2/P1 mixed, generalized Newton: F_n = {mixed_newton:.4f} N, the nested loops' to 1e-6")
triangles = sltest.read_prm(os.path.join(root, "prm", "patin_elastic_triangles.prm"))
for entry in ("set Poisson's ratio = 0.3", "set Finite element pair  = P1/P1"):
    check(entry in triangles, f"prm/patin_elastic_triangles.prm sets '{entry}'")
triangles = triangles.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {NU}")
p2 = triangles.replace("set Finite element pair  = P1/P1", "set Finite element pair  = P2/P1")
p2_mixed = normal_force("P2P1-mixed", p2 + formulation("mixed"))
check(abs(p2_mixed - reference) < 0.01 * reference, f"patin on triangles, P2/P1 mixed: F_n = {p2_mixed:.0f} N, "
      f"{(p2_mixed - reference) / reference:+.2%} from Q2/P2's")
code, log = sltest.run(executable, triangles + formulation("mixed"), f"{workdir}/patin-P1P1-mixed",
                       expect_success=False)
check(code == 1 and "Material/Volumetric formulation = mixed" in log and "P2/P1" in log,
      f"patin on triangles, P1/P1 mixed: refused naming the entry and P2 (exit code {code})")
f_bar_newton = normal_force("Q1P1-F-bar-newton", patin + formulation("F-bar") + sltest.GENERALIZED_NEWTON)
check(abs(f_bar_newton - f_bar) < 1e-6 * f_bar,
      f"patin, Q1/P1 F-bar, generalized Newton: F_n = {f_bar_newton:.4f} N, the nested loops' to 1e-6")

# --- the block in 3D -------------------------------------------------------------------------
# prm/patin_3d.prm (linear elastic, Q1/P1) at nu = 0.4999: the displacement formulation locks; on
# its box cells the mean of tr grad u of a trilinear field over the 2 x 2 x 2 Gauss points is its
# centre value, so the mean dilatation (mixed) and B-bar (F-bar) give the same force
block_3d = sltest.read_prm(os.path.join(root, "prm", "patin_3d.prm"))
check("set Poisson's ratio = 0.3" in block_3d, "prm/patin_3d.prm sets nu = 0.3")
block_3d = block_3d.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {NU}")
forces_3d = {name: normal_force(f"3d-{name}", block_3d + formulation(name)) for name in ("displacement", "F-bar", "mixed")}
check(forces_3d["displacement"] > 3 * forces_3d["F-bar"],
      f"3D block: the displacement formulation locks, F_n = {forces_3d['displacement']:.4g} N, "
      f"{forces_3d['displacement'] / forces_3d['F-bar']:.1f} x F-bar's")
check(abs(forces_3d["mixed"] - forces_3d["F-bar"]) < 1e-8 * forces_3d["F-bar"],
      f"3D block: Q1 mixed {forces_3d['mixed']:.6g} N = F-bar's {forces_3d['F-bar']:.6g} N to 1e-8")

# --- two bodies: the contact patch test at nu = 0.4999 with F-bar ------------------------------
# a uniform stress is a homogeneous deformation, which F-bar leaves unchanged: the pressure is
# the applied one at every node on the non-matching interface
patch = sltest.read_prm(os.path.join(root, "prm", "contact_patch_test.prm"))
check("set Poisson's ratio = 0.3" in patch, "prm/contact_patch_test.prm sets nu = 0.3")
check("set Finite element pair  = Q1/P1" in patch, "prm/contact_patch_test.prm sets Q1/P1")
for pair, name in (("Q1/P1", "F-bar"), ("Q2/P1", "mixed")):
    out = f"{workdir}/patch-{name}"
    sltest.run(executable, patch.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {NU}")
               .replace("set Finite element pair  = Q1/P1", f"set Finite element pair  = {pair}")
               + formulation(name), out, ranks=2)
    values = [row["contact_pressure_MPa"] for row in sltest.last_profile(out + "/output")]
    error = max(abs(v - 100.) for v in values) / 100.
    check(values and error < 1e-8, f"contact patch test, {pair} {name}, nu = {NU}, 2 ranks: {len(values)} nodes, "
          f"max |p - 100| / 100 = {error:.1e}")

# --- Hertz ---------------------------------------------------------------------------------


def hertz(local, nu, name):
    text = hertz_scene(2, "Q1/P1", local, 0.25)
    if "set Poisson's ratio = 0.3" not in text:
        raise SystemExit("FAIL: prm/hertz_cylinder.prm has no 'set Poisson's ratio = 0.3'")
    text = text.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {nu}") + formulation(name)
    out = f"{workdir}/hertz-{nu}-{name}-{local}"
    sltest.run(executable, text, out)
    force = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
    return hertz_errors(2, force, sltest.last_profile(out + "/output"), nu=nu)


locked = hertz(4, NU, "displacement")
check(locked["l2_error"] > 0.5, f"Hertz, displacement formulation locks: L2 error {locked['l2_error']:.1%}")
runs = [hertz(local, NU, "F-bar") for local in (4, 5, 6)]
sltest.check_hertz_sequence(check, runs, "Hertz, F-bar", 0.7)

# --- Cook's membrane -------------------------------------------------------------------------
# prm/cook_membrane.prm (nu = 0.4999, small strain): the vertical displacement of the corner
# (48, 44), the gap of that corner of the contact boundary to a plane 100 mm below, minus 144
cook = sltest.read_prm(os.path.join(root, "prm", "cook_membrane.prm"))
check("meshes/cook_membrane.geo" in cook, "prm/cook_membrane.prm names its mesh")


def cook_corner(n, pair, name):
    out = f"{workdir}/cook-{n}-{pair.replace('/', '')}-{name}"
    os.makedirs(out, exist_ok=True)
    text = (cook + sltest.nested_set("Geometry/gmsh/Mesh file", cook_membrane.mesh_file(out, n))
            + sltest.nested_set("Contact/Finite element pair", pair) + formulation(name))
    sltest.run(executable, text, out)
    return cook_membrane.corner_displacement(sltest.last_profile(out + "/output"))


f_bar = [cook_corner(n, "Q1/P1", "F-bar") for n in (4, 8, 16)]
q2_mixed = [cook_corner(n, "Q2/P1", "mixed") for n in (4, 8, 16)]
quadratic = cook_corner(16, "Q2/P1", "displacement")
locked = cook_corner(16, "Q1/P1", "displacement")
check(f_bar[0] < f_bar[1] < f_bar[2] and f_bar[2] - f_bar[1] < 0.6 * (f_bar[1] - f_bar[0]),
      f"Cook, Q1/P1 F-bar converges: {', '.join(f'{v:.4f}' for v in f_bar)} mm on 4, 8, 16 cells per edge")
check(abs(f_bar[2] - quadratic) < 0.02 * quadratic,
      f"Cook, 16 x 16: F-bar {f_bar[2]:.4f} mm within 2 % of Q2/P1's {quadratic:.4f} mm")
check(max(q2_mixed) - min(q2_mixed) < 0.005 * q2_mixed[2] and abs(q2_mixed[2] - f_bar[2]) < 0.02 * f_bar[2],
      f"Cook, Q2/P1 mixed converged from 4 cells per edge on: {', '.join(f'{v:.4f}' for v in q2_mixed)} mm "
      f"on 4, 8, 16 (spread under 0.5 %), within 2 % of F-bar's on 16 x 16")
check(locked < 0.5 * f_bar[2], f"Cook, 16 x 16: the Q1 displacement formulation locks, {locked:.4f} mm")
check.finish()
