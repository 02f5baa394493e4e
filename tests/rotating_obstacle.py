#!/usr/bin/python3
"""A rigid obstacle turned by a function of time (`Obstacle/Motion/Rotation` about `Rotation
centre`, with the translation of `Obstacle/Motion`) against the same scene with the obstacle
fixed and the body moved by the inverse motion instead: a Galilean check of the rotation.

The body moved instead is turned as a whole (its held face by phi^-1(X) - X, a rotation of
0.04 rad), so the two problems are the same up to a rotation of the deformed configuration
when the material is objective (neo-Hookean here) and the slip is measured against the turning
obstacle: the slave point's start position carried by the obstacle's motion over the step
(doc/formulation.md, "Moving obstacles"). The contact forces and the reactions of the held face
then agree, turned by the obstacle's angle, at every step to the Newton tolerance (scaled
residual 1e-8 of each run: 1e-6 of the largest force), and to the loops' tolerance 1e-4 with
the nested loops (their geometry and friction loops stop at 1e-4 of the change). The slip
measured as the chord of the obstacle's material point (x2(t_n+1) - x2(t_n)) instead would
differ by the angle step times the gap; measured against the fixed obstacle by mu F_n.

- prm/rotating_roller.prm: an eccentric rigid roller (a cylinder turning 0.04 rad about an axis
  5 mm off its own) pressed into a block held at its top, with friction mu = 0.2;
- a plane pressed in the same way, then tilted by 0.001 rad about a point 450 mm below it
  (flat, but its normal turns: it is paired anew each step);
both with the generalized Newton, the roller also with the nested loops. The roller's surface
written per step (obstacle.pvd) is where the motion puts it."""
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
roller = sltest.read_prm(os.path.join(root, "prm", "rotating_roller.prm")).replace(
    "set Global refinements = 5", "set Global refinements = 4")
TRANSLATION = "set Function expression = 0; d*min(2*t, 1)"
ANGLE = "set Function expression = theta*max(2*t - 1, 0)"
CENTRE = "set Rotation centre = 0, -45"
for text in (TRANSLATION, ANGLE, CENTRE, "set Global refinements = 4"):
    check(text in roller, f"the scene has '{text}'")
D, CY = 0.3, -45.0


def angle(t, theta):
    return theta * max(2 * t - 1, 0)


def body_moved(scene, theta, cy):
    """The obstacle fixed, the held face (id 3) moved by phi^-1(X) - X with
    phi(X) = c + d + R(theta) (X - c), c = (0, cy), d = (0, D min(2t, 1))."""
    fixed = scene.replace(TRANSLATION, "set Function expression = 0; 0").replace(
        ANGLE, "set Function expression = 0")
    inverse = (f"      set Function constants  = theta={theta!r}, cy={cy!r}, d={D!r}\n"
               "      set Function expression = \\\n"
               "        cos(theta*max(2*t - 1, 0))*x + sin(theta*max(2*t - 1, 0))*(y - cy - d*min(2*t, 1)) - x; \\\n"
               "        cy - sin(theta*max(2*t - 1, 0))*x + cos(theta*max(2*t - 1, 0))*(y - cy - d*min(2*t, 1)) - y\n")
    return fixed.replace("    set Components  = x, y\n",
                         "    set Components  = x, y\n    subsection Displacement\n" + inverse + "    end\n", 1)


plane = ("  set Model = ball\n  subsection ball\n    set Center = 0, -50\n    set Radius = 50\n  end\n",
         "  set Model = plane\n  subsection plane\n    set Point  = 0, 0\n    set Normal = 0, 1\n  end\n")
check(plane[0] in roller, "the scene has the roller")
# the plane turns about a point 450 mm below it: it slides 0.45 mm while tilting by 0.001 rad
tilted = roller.replace(*plane).replace("theta=0.04", "theta=0.001").replace(CENTRE, "set Rotation centre = 0, -450")
VECTORS = (("contact_force_x_N", "contact_force_y_N"), ("reaction_boundary_3_x_N", "reaction_boundary_3_y_N"))
SCALARS = ("normal_force_N", "tangential_force_N")

for name, moving, theta, cy, loops, tolerance in (
        ("roller, generalized Newton", roller, 0.04, CY, sltest.GENERALIZED_NEWTON, 1e-6),
        ("roller, nested loops", roller, 0.04, CY, "", 1e-4),
        ("tilting plane, generalized Newton", tilted, 0.001, -450.0, sltest.GENERALIZED_NEWTON, 1e-6)):
    rows = {}
    for case, text in (("obstacle moved", moving), ("body moved", body_moved(moving, theta, cy))):
        out = os.path.join(workdir, (name + " " + case).replace(" ", "_").replace(",", ""))
        sltest.run(executable, text + loops + sltest.QUIET_OUTPUT, out)
        rows[case] = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    a, b = rows["obstacle moved"], rows["body moved"]
    scale = max(abs(row[c]) for row in a for pair in VECTORS for c in pair)
    worst = 0.
    for x, y in zip(a, b):
        c, s = math.cos(angle(x["time"], theta)), math.sin(angle(x["time"], theta))
        for cx, cy in VECTORS:
            # the body-moved scene is the obstacle-moved one turned by -theta
            worst = max(worst, abs(x[cx] - (c * y[cx] - s * y[cy])), abs(x[cy] - (s * y[cx] + c * y[cy])))
        worst = max(worst, max(abs(x[k] - y[k]) for k in SCALARS))
    slid = [row for row in a if row["time"] > 0.5 and row["points_stick"] == 0 and row["points_slip"] > 0]
    check(len(a) == len(b) == 10 and worst <= tolerance * scale,
          f"{name}: forces and reactions equal up to the rotation at all {len(a)} steps (largest "
          f"difference {worst:.1e} N against forces up to {scale:.4g} N)")
    check(len(slid) >= 3, f"{name}: the obstacle drags the body, every contact point slips at "
          f"{len(slid)} steps")

# the obstacle in the output: obstacle_00010.vtu is obstacle_00000.vtu moved by phi(t = 1)
out = os.path.join(workdir, "roller_output")
sltest.run(executable, roller + sltest.GENERALIZED_NEWTON +
           "\nsubsection Output\n  set Output directory = output\nend\n", out)
try:
    points = []
    for step in (0, 10):
        data = sltest.read_vtu(os.path.join(out, "output", f"obstacle_{step:05d}.vtu")).GetPoints()
        points.append([data.GetPoint(i) for i in range(data.GetNumberOfPoints())])
    c, s = math.cos(0.04), math.sin(0.04)
    worst = 0.
    for X, x in zip(*points):
        # phi(X) = c + d + R (X - c), c = (0, CY), d = (0, D)
        px, py = X[0], X[1] - CY
        worst = max(worst, abs(x[0] - (c * px - s * py)), abs(x[1] - (CY + D + s * px + c * py)))
    check(len(points[0]) == len(points[1]) > 100 and worst <= 1e-4,
          f"obstacle_00010.vtu: the roller's {len(points[1])} surface vertices where the motion puts "
          f"them (off by {worst:.1e} mm; float32 coordinates)")
    # contrib/render_pvd.py draws the obstacle where contrib/run_output.py's moved_obstacle()
    # finds it in those files: the roller's centre phi(C), C = (0, -50) at rest
    run_output = sltest.run_output
    rest = run_output.rigid_obstacle(run_output.run_parameters(os.path.join(out, "output")))
    moved = run_output.moved_obstacle(rest, os.path.join(out, "output"), 10)
    centre = (-s * (-50 - CY), CY + D + c * (-50 - CY))
    off = max(abs(moved["center"][i] - centre[i]) for i in range(2))
    check(rest["center"][:2] == [0, -50] and off <= 1e-4,
          f"run_output.moved_obstacle(): the roller's centre at t = 1 is ({moved['center'][0]:.6f}, "
          f"{moved['center'][1]:.6f}) mm (phi(C) = ({centre[0]:.6f}, {centre[1]:.6f}))")
    out = os.path.join(workdir, "plane_output")
    sltest.run(executable, tilted + sltest.GENERALIZED_NEWTON +
               "\nsubsection Output\n  set Output directory = output\nend\n", out)
    rest = run_output.rigid_obstacle(run_output.run_parameters(os.path.join(out, "output")))
    normal = run_output.moved_obstacle(rest, os.path.join(out, "output"), 10)["normal"]
    off = max(abs(normal[0] + math.sin(0.001)), abs(normal[1] - math.cos(0.001)))
    check(off <= 1e-6, f"run_output.moved_obstacle(): the tilted plane's normal at t = 1 is "
          f"({normal[0]:.7f}, {normal[1]:.7f}), (-sin 0.001, cos 0.001) to {off:.1e}")
except ImportError:
    check(False, "python3-vtk9 is needed to read the VTU")
check.finish()
