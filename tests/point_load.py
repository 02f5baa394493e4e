#!/usr/bin/python3
"""Point loads (`Boundary conditions/Point load <name>`: a force F(t) on the vertex at `Point`) on
the block of prm/patin_elastic.prm (100 x 50 mm, E = 200000 MPa) resting on the rigid plane with
friction mu = 0.3 and no other support: one node at the middle of the top face carries
P = 1000 N/mm downwards until t = 0.5, then also Q = 0.5 mu P sideways.

- The contact force balances the load at every step: F_n = P(t) and F_t = Q(t) to 1e-8 of P
  (generalized Newton: the contact force is that of the last assembled system); the body
  sticks in the middle, so it neither slides nor turns.
- The same on 2 MPI ranks.
- Refused with a message: a point that is not a vertex of the mesh.
- A point load on a vertex a Dirichlet condition holds (the patin's pressed top face) is taken by
  the support's reaction: the run warns, naming the load and the held components; the free
  vertex above does not."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
base = sltest.read_prm(os.path.join(root, "prm", "patin_elastic.prm"))
P, MU = 1000.0, 0.3
Q = 0.5 * MU * P
start, end = base.index("subsection Boundary conditions"), base.index("subsection Load stepping")


def scene(point):
    text = base[:start] + f"""subsection Boundary conditions
  subsection Point load middle
    set Point = {point}
    subsection Force
      set Function expression = {Q}*max(2*t - 1, 0); -{P}*min(2*t, 1)
    end
  end
end
""" + base[end:]
    return text.replace("set Friction coefficient = 0.1", f"set Friction coefficient = {MU}")


text = scene("0, 50")
check(f"set Friction coefficient = {MU}" in text, "the scene has the friction coefficient")
runs = {}
for ranks in (1, 2):
    out = os.path.join(workdir, f"np{ranks}")
    log = sltest.run(executable, text + sltest.GENERALIZED_NEWTON + sltest.QUIET_OUTPUT, out,
                     ranks=ranks)[1]
    check("holds its vertex" not in log, f"{ranks} rank(s): no warning of a held point load")
    rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    runs[ranks] = rows
    worst = max(max(abs(row["normal_force_N"] - P * min(2 * row["time"], 1)),
                    abs(row["tangential_force_N"] - Q * max(2 * row["time"] - 1, 0))) for row in rows)
    check(len(rows) == 10 and worst <= 1e-8 * P,
          f"{ranks} rank(s): F_n = P(t) and F_t = Q(t) at all {len(rows)} steps (largest difference {worst:.1e} N/mm)")
    check(rows[-1]["points_stick"] > 0, f"{ranks} rank(s): {int(rows[-1]['points_stick'])} points stick at the end")
worst = max(abs(a[c] - b[c]) for a, b in zip(runs[1], runs[2]) for c in ("normal_force_N", "tangential_force_N"))
check(worst <= 1e-8 * P, f"2 ranks: the forces of 1 rank (largest difference {worst:.1e} N/mm)")
code, log = sltest.run(executable, scene("0.1, 50") + sltest.QUIET_OUTPUT, os.path.join(workdir, "off"),
                       expect_success=False)
check(code == 1 and "Point load middle/Point" in log and "no vertex" in log,
      f"a point off the vertices: refused ({log.strip().splitlines()[-1][:160]})")
held = base.replace("subsection Boundary conditions\n", f"""subsection Boundary conditions
  subsection Point load top
    set Point = 0, 50
    subsection Force
      set Function expression = {Q}*t; -{P}*t
    end
  end
""", 1) + sltest.nested_set("Load stepping/Number of load steps", 2)
code, log = sltest.run(executable, held + sltest.QUIET_OUTPUT, os.path.join(workdir, "held"),
                       expect_success=False)
check(code == 0 and "WARNING: Boundary conditions/Point load top: a Dirichlet condition holds its "
      "vertex in x, y" in log, f"a point load on a held vertex: warned (exit code {code})")
check.finish()
