#!/usr/bin/python3
"""Curved boundaries of Gmsh meshes (`Geometry/gmsh/Spherical boundaries`):
a half disc (tests/scenes/half_disc.geo, coarse quadrilaterals) pressed onto
a rigid plane, refined twice.

Checks: with the arc declared, every contact node of the refined mesh lies on
the circle (distance to the centre R to 1e-10 R); without it the refined
nodes stay on the coarse facets (some are off the circle by more than 1e-4 R:
what the option is for); a centre the arc's vertices are not equidistant
from, an unknown boundary and a malformed centre stop the run with exit 1 and
a message naming the entry."""
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
R = 10.0
geo = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "half_disc.geo")


def scene(spheres):
    return f"""
subsection Geometry
  set Model = gmsh
  subsection gmsh
    set Mesh file = {geo}
    set Global refinements = 2
    set Spherical boundaries = {spheres}
  end
end
subsection Contact
  set Contact boundary ids = contact
  subsection Friction law
    subsection Coulomb
      set Friction coefficient = 0
    end
  end
end
subsection Boundary conditions
  subsection Dirichlet 1
    set Boundary id = top
    subsection Displacement
      set Function expression = 0; -0.01*t
    end
  end
end
"""


def distances(name, spheres):
    out = os.path.join(workdir, name)
    if not sltest.run_checked(executable, scene(spheres), out, check, name):
        return []
    return [math.hypot(row["x_mm"], row["y_mm"] - R) for row in
            sltest.last_profile(os.path.join(out, "output"))]


on_arc = distances("declared", "contact: 0, 10")
check(len(on_arc) > 16 and max(abs(d - R) for d in on_arc) < 1e-10 * R,
      f"declared arc: the {len(on_arc)} contact nodes are on the circle "
      f"(largest distance error {max((abs(d - R) for d in on_arc), default=-1):.1e} mm)")
faceted = distances("undeclared", "")
check(len(faceted) == len(on_arc) and max(abs(d - R) for d in faceted) > 1e-4 * R,
      f"undeclared arc: the refined nodes stay on the facets "
      f"(largest distance error {max((abs(d - R) for d in faceted), default=-1):.1e} mm)")

for name, spheres, expected in (("wrong centre", "contact: 0, 9", "not on one sphere"),
                                ("unknown boundary", "bottom: 0, 10", "has no boundary 'bottom'"),
                                ("malformed centre", "contact: 0; 10", "must be 2 numbers"),
                                ("no centre", "contact", "is not `boundary: centre`")):
    code, log = sltest.run(executable, scene(spheres), os.path.join(workdir, name.replace(" ", "_")),
                           expect_success=False)
    check(code == 1 and "Geometry/gmsh/Spherical boundaries" in log and expected in log,
          f"{name} ('{spheres}'): exit {code}, the message names the entry and says '{expected}'")
    print("      " + log.strip().splitlines()[-1][:300])
check.finish()
