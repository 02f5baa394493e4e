#!/usr/bin/python3
"""A body meant to rest on the obstacle, placed within round-off of it, or not
touching it at all while its Dirichlet conditions leave it free to move.

A half cylinder (radius 50) pressed by a traction on its flat top (held in x
there) onto a rigid plane, μ = 0.3: with the plane 1e-14 mm below its lowest
vertex, that vertex must start in contact exactly as when it touches (the plane
at 0): same loop counts, same forces. (It used to start open: 11 status
iterations in the first step instead of 5, and users met Newton stalling.)
Both with the nodal (Gauss-Lobatto) and the Gauss contact quadrature (whose
points miss the lowest vertex: the nearest ones are put in contact).

The same body 1 mm above the plane is lowered onto it (its nearest points
start in contact: the loads alone cannot move an unheld body in a quasi-static
step, its system is singular) and carries the load; pulled upwards, it is not
supported: the run stops at once naming the free motion (it used to "converge"
with a force residual of 621 N and the body flown away)."""
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
COLUMNS = ("geometry_iterations", "friction_iterations", "status_iterations", "newton_iterations",
           "points_in_contact", "points_stick", "points_slip")
for quadrature in ("Gauss-Lobatto", "Gauss"):
    runs = {}
    for y in ("0", "-1e-14"):
        out = f"{workdir}/{quadrature}-{y}"
        code, log = sltest.run(executable, sltest.scene("resting_cylinder", Y=y, QUADRATURE=quadrature,
                                                        LOAD="-100*t") + sltest.QUIET_OUTPUT,
                               out, expect_success=False)
        check(code == 0, f"{quadrature}, plane at y = {y}: exit code {code}")
        runs[y] = sltest.read_csv(out + "/output/statistics.csv") if code == 0 else []
    touching, above = runs["0"], runs["-1e-14"]
    check(len(touching) == len(above) == 2, f"{quadrature}: both runs take the 2 load steps")
    for a, b in zip(touching, above):
        same = all(a[c] == b[c] for c in COLUMNS)
        check(same, f"{quadrature} step {a['step']:.0f}: loop counts and statuses equal "
                    f"(status iterations {b['status_iterations']:.0f} vs {a['status_iterations']:.0f})")
        # force control: F_n is the applied load in both; the check is that both carry it
        check(abs(a["normal_force_N"] - b["normal_force_N"]) <= 1e-8 * a["normal_force_N"],
              f"{quadrature} step {a['step']:.0f}: F_n {b['normal_force_N']:.6f} = {a['normal_force_N']:.6f}")
for name, y, load, quadrature in (("lowered", "-1", "-100*t", "Gauss-Lobatto"),
                                  ("pulled", "0", "100*t", "Gauss-Lobatto")):
    out = f"{workdir}/{name}"
    code, log = sltest.run(executable, sltest.scene("resting_cylinder", Y=y, QUADRATURE=quadrature, LOAD=load) +
                           sltest.QUIET_OUTPUT, out, expect_success=False)
    if name == "lowered":
        rows = sltest.read_csv(out + "/output/statistics.csv") if code == 0 else []
        check(code == 0 and "nothing touches the obstacle and the Dirichlet conditions leave" in log and
              "(gap 1 mm) start in contact" in log,
              f"1 mm above: the nearest points start in contact, exit code {code}")
        check(len(rows) == 2 and abs(rows[-1]["normal_force_N"] - 10000.) <= 1e-8 * 10000.,
              "1 mm above: the load, 100 MPa on the 100 mm wide top, is carried by contact")
    else:
        check(code == 2 and "the body is not supported" in log and "the translation along y" in log and
              "cutting the step" not in log,
              f"pulled off: stops at once naming the free translation along y, exit code {code}")
check.finish()
