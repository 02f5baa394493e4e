#!/usr/bin/python3
"""3D half ball (radius 50, 2 global and 3 local refinements of radius 15), pressed
by 0.1 mm: with `Contact zone radius` 14 or 18 the candidate contact surface ends
among refined faces and carries multipliers at hanging vertices; it used to stop
at the first assembly with "An error with error number 2 occurred while calling a
Trilinos function". The contact area (radius ~ sqrt(R delta) = 2.2 mm) lies well
inside every zone, so the zone radius 10 (no hanging multiplier), 14 and 18 are the
same discrete problem on the same mesh: the normal force must agree to solver
tolerance."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
here = os.path.dirname(os.path.abspath(__file__))
sphere = sltest.read_prm(os.path.join(here, "..", "prm", "hertz_sphere.prm"))
forces = {}
for zone in (10, 14, 18):
    text = (sphere + sltest.nested_set("Geometry/half ball/Radius", 50) +
            sltest.nested_set("Geometry/half ball/Local refinement radius", 15) +
            sltest.nested_set("Geometry/half ball/Contact zone radius", zone) +
            sltest.nested_set("Boundary conditions/Dirichlet 1/Displacement/Function constants",
                              "delta=0.1"))
    out = f"{workdir}/zone-{zone}"
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, expect_success=False)
    check(code == 0, f"zone radius {zone}: exit code {code}")
    hanging = "multiplier DoFs at hanging nodes of the contact boundary" in log
    check(hanging == (zone != 10), f"zone radius {zone}: hanging multiplier DoFs reported: {hanging}")
    if code == 0:
        forces[zone] = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
    else:
        print(log[-2000:])
if len(forces) == 3:
    for zone in (14, 18):
        check(abs(forces[zone] - forces[10]) <= 1e-8 * forces[10],
              f"zone radius {zone}: F_n {forces[zone]:.6f} = {forces[10]:.6f} (zone 10)")
check.finish()
