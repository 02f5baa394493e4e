#!/usr/bin/python3
"""The generalized Newton and the nested fixed points reach the same solution.

Each scene runs twice: with the seed's nested loops, their fixed-point
tolerances tightened to 1e-10 so that they stop at the same solution, and with
the geometry, friction and status loops all folded into Newton. Forces at every
step and the contact pressure and tangential traction at every contact node of
the last step must agree to 1e-6 relative: both runs end with residuals below
1e-6 N on forces of 1e3 to 1e5 N, so what is left is the loops' tolerance.
The Newton run must report one iteration of each outer loop per step.

Frictionless Hertz by force control (tests/scenes/hertz_force.prm), where the
active set grows from one point to 38 in one step: the generalized Newton's
full steps raise the residual while the set is found, and a line search that
backtracks them needs more iterations than the nested loops (12 against 8, and
step cuts on a finer mesh). The active-set watchdog takes them whole: no more
Newton iterations than the nested loops, no cut.

Scenes: the elastic and neo-Hookean patins (plane obstacle, finite strain for
the second) and a block pressed and slid on a rigid disc / ball with friction,
in 2D and 3D, where the pairing, the normal and the tangents move with the
slave points and are linearised; the elastic patin and the block on the disc
and the ball again on triangles / tetrahedra with P1/P1."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")

TIGHT = """
subsection Nonlinear solver
  subsection Geometry loop
    set Tolerance = 1e-10
  end
  subsection Friction loop
    set Tolerance = 1e-10
  end
end
"""


def patin(name):
    with open(os.path.join(root, "prm", f"patin_{name}.prm")) as f:
        text = f.read()
    return text + "\nsubsection Geometry\n  subsection block\n    set Global refinements = 3\n  end\nend\n"


def block_on_ball(dim):
    """A 20 x 10 (x 10) block pressed by 0.2 mm onto a rigid disc / ball of radius 50,
    then slid by 1 mm along x, mu = 0.3."""
    center = "10, -50" if dim == 2 else "10, 5, -50"
    top = "if(t < 0.5, 0, 2*(t - 0.5)); -0.4*min(t, 0.5)"
    if dim == 3:
        top = "if(t < 0.5, 0, 2*(t - 0.5)); 0; -0.4*min(t, 0.5)"
    return f"""
set Dimension = {dim}
subsection Geometry
  set Model = block
  subsection block
    set Length = 20
    set Height = 10
    set Width = 10
    set Subdivisions = {"4, 2" if dim == 2 else "2, 1, 1"}
    set Global refinements = {2 if dim == 2 else 1}
  end
end
subsection Obstacle
  set Model = ball
  subsection ball
    set Center = {center}
    set Radius = 50
  end
end
""" + sltest.linear_elastic(1000, 0.3) + sltest.coulomb_contact("  set r_n = 100\n  set r_t = 10\n", 0.3) + f"""subsection Boundary conditions
  subsection Dirichlet 1
    set Boundary id = 3
    set Components = {"x, y" if dim == 2 else "x, y, z"}
    subsection Displacement
      set Function expression = {top}
      set Variable names = {"x,y,t" if dim == 2 else "x,y,z,t"}
    end
  end
end
subsection Load stepping
  set Number of load steps = 6
end
"""


SIMPLICES = ("\nsubsection Geometry\n  subsection block\n    set Cell shape = simplex\n  end\nend\n"
             "subsection Contact\n  set Finite element pair = P1/P1\nend\n")
scenes = [("elastic patin", patin("elastic")), ("neo-Hookean patin", patin("neo_hookean")),
          ("2D block on a disc", block_on_ball(2)), ("3D block on a ball", block_on_ball(3)),
          ("Hertz by force", sltest.scene("hertz_force")),
          ("elastic patin, triangles", sltest.read_prm(os.path.join(root, "prm", "patin_elastic_triangles.prm"))),
          ("2D block on a disc, triangles", block_on_ball(2) + SIMPLICES),
          ("3D block on a ball, tetrahedra", block_on_ball(3) + SIMPLICES)]
for name, text in scenes:
    tag = name.replace(" ", "_")
    runs = {}
    for algorithm, extra in (("nested", TIGHT), ("newton", sltest.GENERALIZED_NEWTON)):
        out = f"{workdir}/{tag}/{algorithm}"
        if not sltest.run_checked(executable, text + extra, out, check, f"{name}, {algorithm}"):
            break
        runs[algorithm] = (sltest.read_csv(f"{out}/output/statistics.csv"),
                           sltest.last_profile(f"{out}/output"))
    if len(runs) != 2:
        continue
    (nested, nested_profile), (newton, newton_profile) = runs["nested"], runs["newton"]
    check(len(nested) == len(newton), f"{name}: {len(nested)} and {len(newton)} load steps")
    check(all(s["geometry_iterations"] == s["friction_iterations"] == s["status_iterations"] == 1
              for s in newton), f"{name}, newton: one iteration of each outer loop per step")
    scale = max(abs(s["normal_force_N"]) for s in nested)
    force_difference = max(abs(a[key] - b[key]) for a, b in zip(nested, newton)
                           for key in ("normal_force_N", "tangential_force_N"))
    check(force_difference <= 1e-6 * scale,
          f"{name}: forces differ by {force_difference:.2e} N (<= 1e-6 x {scale:.4g} N)")
    check(len(nested_profile) == len(newton_profile) > 0,
          f"{name}: {len(newton_profile)} contact nodes in both profiles")
    frictionless = all(s["tangential_force_N"] == 0 for s in nested)
    for field in ("contact_pressure_MPa",) + (() if frictionless else ("tangential_traction_x_MPa",)):
        size = max(abs(p[field]) for p in nested_profile)
        difference = max(abs(a[field] - b[field]) for a, b in zip(nested_profile, newton_profile))
        check(size > 0 and difference <= 1e-6 * size,
              f"{name}: {field} differs by {difference:.2e} (<= 1e-6 x {size:.4g})")
    totals = [sum(s["newton_iterations"] for s in run) for run in (nested, newton)]
    print(f"      {name}: Newton iterations nested {totals[0]:.0f}, generalized Newton {totals[1]:.0f}")
    if name == "Hertz by force":
        check(totals[1] <= totals[0] and all(s["step_cuts"] == 0 for s in newton),
              f"{name}: generalized Newton {totals[1]:.0f} iterations (at most the nested loops' "
              f"{totals[0]:.0f}), {sum(s['step_cuts'] for s in newton):.0f} step cuts (none)")
check.finish()
