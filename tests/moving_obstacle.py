#!/usr/bin/python3
"""A rigid obstacle moved by a function of time (`Obstacle/Motion`, a translation d(t)) against
the same scene with the obstacle fixed and the body moved by -d(t) instead: a Galilean check.
The two problems differ by a rigid translation, which strains nothing, so the discrete solutions
are the same up to it: the contact forces and the reactions of the held face agree at every
step to the Newton tolerance (the scaled residual 1e-8 of each run: 1e-6 of the largest force
here, measured 3e-8). A slip measured against the fixed obstacle instead of the moving one
would change the tangential force by mu F_n.

- prm/moving_punch.prm: a rigid cylindrical punch (`ball`, curved: the geometry loop pairs anew)
  pressed into a block held at its top, then slid along it with friction mu = 0.2;
- the same with a plane (flat: the pairing is frozen for the step and follows the obstacle);
both with the generalized Newton, the punch also with the nested loops. The punch's surface
written per step (obstacle.pvd) is where the motion puts it (their geometry and
friction loops stop at their tolerance 1e-4 on the change of the displacement and the threshold,
so the forces agree to that tolerance: 1e-4 of the largest; measured 7.5e-6)."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
punch = sltest.read_prm(os.path.join(root, "prm", "moving_punch.prm"))
MOTION = "set Function expression = s*max(2*t - 1, 0); d*min(2*t, 1)"
check(MOTION in punch, "the scene has the punch's motion")
# the body moved instead: the held face by -d(t), the obstacle fixed
fixed = punch.replace(MOTION, "set Function expression = 0; 0").replace(
    "    set Components  = x, y\n", "    set Components  = x, y\n    subsection Displacement\n"
    "      set Function constants  = s=2, d=0.3\n"
    "      set Function expression = -s*max(2*t - 1, 0); -d*min(2*t, 1)\n    end\n", 1)
plane = ("  set Model = ball\n  subsection ball\n    set Center = 0, -50\n    set Radius = 50\n  end\n",
         "  set Model = plane\n  subsection plane\n    set Point  = 0, 0.01\n    set Normal = 0, 1\n  end\n")
check(plane[0] in punch, "the scene has the ball")
COLUMNS = ("normal_force_N", "tangential_force_N", "contact_force_x_N", "contact_force_y_N",
           "reaction_boundary_3_x_N", "reaction_boundary_3_y_N")

for name, moving, moved, loops, tolerance in (
        ("punch, generalized Newton", punch, fixed, sltest.GENERALIZED_NEWTON, 1e-6),
        ("punch, nested loops", punch, fixed, "", 1e-4),
        ("plane, generalized Newton", punch.replace(*plane), fixed.replace(*plane), sltest.GENERALIZED_NEWTON, 1e-6)):
    rows = {}
    for case, text in (("obstacle moved", moving), ("body moved", moved)):
        out = os.path.join(workdir, (name + " " + case).replace(" ", "_").replace(",", ""))
        sltest.run(executable, text + loops + sltest.QUIET_OUTPUT, out)
        rows[case] = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    a, b = rows["obstacle moved"], rows["body moved"]
    scale = max(abs(row[c]) for row in a for c in COLUMNS)
    worst = max(abs(x[c] - y[c]) for x, y in zip(a, b) for c in COLUMNS)
    slid = [row for row in a if row["time"] > 0.5 and row["points_stick"] == 0 and row["points_slip"] > 0]
    check(len(a) == len(b) == 10 and worst <= tolerance * scale,
          f"{name}: forces and reactions equal at all {len(a)} steps (largest difference {worst:.1e} N "
          f"against forces up to {scale:.4g} N)")
    check(len(slid) >= 3, f"{name}: the obstacle slides along the body, every contact point slips at "
          f"{len(slid)} steps")
    if name.startswith("plane"):
        # (on the punch the points' tangents turn along the arc, so the resultants' ratio is
        # below mu by the curvature, 1 - cos(a/R) = 4e-4 here)
        check(all(abs(row["tangential_force_N"] - 0.2 * row["normal_force_N"]) <= 1e-6 * row["normal_force_N"]
                  for row in slid), f"{name}: F_t = mu F_n at those steps")

# the obstacle in the output: obstacle.pvd lists a surface per step, moved by d(t)
out = os.path.join(workdir, "punch_output")
sltest.run(executable, punch + "\nsubsection Output\n  set Output directory = output\nend\n", out)
with open(os.path.join(out, "output", "obstacle.pvd")) as f:
    listed = f.read().count("obstacle_")
check(listed == 11, f"obstacle.pvd lists the surface at the 11 output times ({listed})")
try:
    bounds = [sltest.read_vtu(os.path.join(out, "output", f"obstacle_{step:05d}.vtu")).GetBounds()
              for step in (0, 10)]
    # the circle of radius 50 about (0, -50), then moved by d(1) = (2, 0.3); float32 coordinates
    expected = [(-50, 50, -100, 0), (-48, 52, -99.7, 0.3)]
    worst = max(abs(b[k] - e[k]) for b, e in zip(bounds, expected) for k in range(4))
    check(worst <= 1e-4, f"obstacle_00000.vtu and obstacle_00010.vtu: the punch at rest and moved by "
          f"(2, 0.3) mm (bounds off by {worst:.1e} mm)")
except ImportError:
    check(False, "python3-vtk9 is needed to read the VTU")
check.finish()
