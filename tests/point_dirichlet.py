#!/usr/bin/python3
"""Single-node Dirichlet conditions (`Boundary conditions/Dirichlet <name>` with `Point`: the
displacement of the vertex there prescribed in some components) on the block of
prm/patin_elastic.prm (100 x 50 mm) resting on the rigid plane, with no boundary held:

- frictionless, a pressure p and a shear q on the top face, one node (the top-left corner) held
  in x: the node takes the whole horizontal load, reaction_point_corner_x_N = -q L, and the
  contact the vertical one, F_n = p L, to 1e-8 at every step; without the node the
  frictionless contact leaves the body free to slide, and the run warns, naming the
  translation;
- with friction mu = 0.3, the top middle node pushed down by d(t): the node's reaction balances
  the contact force, -reaction_point_push_y_N = F_n, and the friction force vanishes with
  nothing pulling sideways, to 1e-8 of F_n at every step; the same on 2 MPI ranks;
- a node held on a boundary that is held too, in the same component: the node's condition
  prescribes it, whichever subsection comes first in the file;
- refused with a message: Point and Boundary id both given, a point that is not a vertex."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
base = sltest.read_prm(os.path.join(root, "prm", "patin_elastic.prm"))
base = base.replace("set Global refinements = 4", "set Global refinements = 3")
start, end = base.index("subsection Boundary conditions"), base.index("subsection Load stepping")
p, q, L = 100.0, 20.0, 100.0


def scene(conditions, mu):
    text = base[:start] + "subsection Boundary conditions\n" + conditions + "end\n" + base[end:]
    return text.replace("set Friction coefficient = 0.1", f"set Friction coefficient = {mu}")


HELD_CORNER = f"""  subsection Neumann top
    set Boundary id = 3
    subsection Traction
      set Function expression = {q}*t; -{p}*t
    end
  end
  subsection Dirichlet corner
    set Point = -50, 50
    set Components = x
  end
"""
out = os.path.join(workdir, "corner")
sltest.run(executable, scene(HELD_CORNER, 0) + sltest.QUIET_OUTPUT, out)
rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
worst = max(max(abs(row["reaction_point_corner_x_N"] + q * L * row["time"]),
                abs(row["normal_force_N"] - p * L * row["time"])) for row in rows)
check(len(rows) == 10 and worst <= 1e-8 * p * L,
      f"corner held in x: reaction -q L and F_n = p L at all {len(rows)} steps "
      f"(largest difference {worst:.1e} N/mm)")

code, log = sltest.run(executable, scene(HELD_CORNER.replace("set Point = -50, 50", "set Point ="), 0)
                       + sltest.QUIET_OUTPUT, os.path.join(workdir, "free"), expect_success=False)
check("WARNING: the body is not held" in log and "translation along x" in log,
      "without the node, frictionless: the run warns that the translation along x is free")

PUSHED = """  subsection Dirichlet push
    set Point = 0, 50
    set Components = y
    subsection Displacement
      set Function expression = 0; -0.05*t
    end
  end
"""
runs = {}
for ranks in (1, 2):
    out = os.path.join(workdir, f"push-np{ranks}")
    # (generalized Newton: the contact force is that of the last assembled system, so the
    # balance holds to the Newton tolerance; the nested friction loop stops on its own criterion)
    sltest.run(executable, scene(PUSHED, 0.3) + sltest.GENERALIZED_NEWTON + sltest.QUIET_OUTPUT, out,
               ranks=ranks)
    rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    runs[ranks] = rows
    force = rows[-1]["normal_force_N"]
    worst = max(max(abs(row["reaction_point_push_y_N"] + row["normal_force_N"]),
                    abs(row["tangential_force_N"])) for row in rows)
    check(force > 0 and worst <= 1e-8 * force,
          f"{ranks} rank(s): the pushed node's reaction balances F_n = {force:.1f} N/mm at all "
          f"{len(rows)} steps, F_t = 0 (largest difference {worst:.1e} N/mm)")
worst = max(abs(a[c] - b[c]) for a, b in zip(runs[1], runs[2])
            for c in ("normal_force_N", "reaction_point_push_y_N"))
check(worst <= 1e-8 * runs[1][-1]["normal_force_N"],
      f"2 ranks: the forces of 1 rank (largest difference {worst:.1e} N/mm)")

# The top's corner pulled sideways by 0.02 t mm while the top is held in x and pushed down by
# 0.05 t mm: the corner's own condition gives its x, the top's its y.
PULLED_CORNER = """  subsection Dirichlet corner
    set Point = -50, 50
    set Components = x
    subsection Displacement
      set Function expression = 0.02*t; 0
    end
  end
  subsection Dirichlet top
    set Boundary id = 3
    set Components = x, y
    subsection Displacement
      set Function expression = 0; -0.05*t
    end
  end
"""
corner, top = PULLED_CORNER.split("  subsection Dirichlet top\n")
for order, conditions in (("corner first", PULLED_CORNER), ("top first", "  subsection Dirichlet top\n" + top + corner)):
    out = os.path.join(workdir, "pulled-" + order.replace(" ", "-"))
    sltest.run(executable, scene(conditions, 0) + "\nsubsection Output\n  set Output directory = output\nend\n", out)
    try:
        vtu = [f for f in sorted(os.listdir(os.path.join(out, "output"))) if f.startswith("solution_00010")
               and f.endswith(".vtu")]
        grid = sltest.read_vtu(os.path.join(out, "output", vtu[0]))
        displacement = grid.GetPointData().GetArray("displacement_mm")
        at = {}
        for i in range(grid.GetNumberOfPoints()):
            x, y, _ = grid.GetPoint(i)
            if abs(y - 50) < 1e-6 and abs(x + 50) < 1e-6 or abs(y - 50) < 1e-6 and abs(x) < 1e-6:
                at["corner" if x < -1 else "middle"] = displacement.GetTuple(i)[:2]
        check(abs(at["corner"][0] - 0.02) <= 1e-6 and abs(at["corner"][1] + 0.05) <= 1e-6
              and abs(at["middle"][0]) <= 1e-6 and abs(at["middle"][1] + 0.05) <= 1e-6,
              f"{order}: the corner moved by {at['corner']} mm (its own x, the top's y), the top's "
              f"middle by {at['middle']} mm (float32 output)")
    except ImportError:
        check(False, "python3-vtk9 is needed to read the VTU")

for name, conditions, words in (
        ("Point and Boundary id", PUSHED.replace("set Point = 0, 50", "set Point = 0, 50\n    set Boundary id = 3"),
         ["Dirichlet push", "both Boundary id and Point"]),
        ("a point off the vertices", PUSHED.replace("set Point = 0, 50", "set Point = 0.1, 50"),
         ["Dirichlet push/Point", "no vertex"]),
        ("a point with one coordinate", PUSHED.replace("set Point = 0, 50", "set Point = 0"),
         ["Dirichlet push/Point", "comma-separated coordinates"])):
    code, log = sltest.run(executable, scene(conditions, 0.3) + sltest.QUIET_OUTPUT,
                           os.path.join(workdir, "refused-" + name.replace(" ", "-")), expect_success=False)
    missing = [w for w in words if w not in log]
    check(code == 1 and not missing, f"refused: {name} ({log.strip().splitlines()[-1][:160]})")
check.finish()
