#!/usr/bin/python3
"""The contact statuses of the elasto-plastic patin with Q2/P1 at the sliding onset cycle between
two active sets with the friction threshold frozen; the step is repeated with the threshold
folded into the generalized Newton (nested_loops.cc, status_loop()) instead of being cut.

prm/patin_elastoplastic.prm with `Finite element pair = Q2/P1`, nested loops, up to t = 0.6 in 6
load steps (the sliding starts at t = 0.5). In the step t = 0.5 -> 0.6 the status loop cycles and
its statuses are folded into the generalized Newton; there, with s = mu lambda_n frozen at the
last step's value (the patin's trailing corner, lambda_n = 485 MPa at t = 0.5), a full step from
the set with the corner closed lands on the set with it open and back: the residual between them
is s times the corner's quadrature weight (24.18 N/mm = 46.43 MPa x 3.125/6 mm) whatever the step,
so three step cuts and 139 Newton iterations in failed attempts did not help.

Checks: exit 0; no step cut, and at most one Newton loop's iterations (its limit, 25, and
the status loop's before it: 60 in all) in the one discarded attempt (statistics.csv); the
normal and tangential contact forces at every step equal those of the same scene solved with all
three loops folded into the generalized Newton (seed §2.3), which solves the same discrete
equations: the runs differ by the nested loops' stopping tolerances (friction and geometry loop
1e-4 relative), so to 1e-3 of the normal force."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
base = sltest.read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                                    "patin_elastoplastic.prm")) + "".join(
    sltest.nested_set(path, value) for path, value in (
        ("Contact/Finite element pair", "Q2/P1"),
        ("Load stepping/End time", 0.6),
        ("Load stepping/Number of load steps", 6)))
LOOP_TOLERANCE = 1e-4  # Nonlinear solver/{Friction,Geometry} loop/Tolerance, their defaults

runs = {}
for name, extra in (("nested", ""), ("generalized_newton", sltest.GENERALIZED_NEWTON)):
    if sltest.run_checked(executable, base + extra, f"{workdir}/{name}", check, name):
        runs[name] = sltest.read_csv(f"{workdir}/{name}/output/statistics.csv")

if "nested" in runs:
    rows = runs["nested"]
    cuts = sum(r["step_cuts"] for r in rows)
    failed = sum(r["failed_attempt_newton_iterations"] for r in rows)
    newton = sum(r["newton_iterations"] for r in rows)
    check(len(rows) == 6 and cuts == 0, f"nested: {len(rows)} load steps (6), {cuts:.0f} step cuts (0)")
    check(failed <= 60, f"nested: {failed:.0f} Newton iterations in failed attempts (at most 60; "
          f"75 to 139 when the cycle was cut), {newton:.0f} in all")
    print(f"nested: folded loops per step {[int(r['folded_loops']) for r in rows]}")
if len(runs) == 2:
    for nested, reference in zip(runs["nested"], runs["generalized_newton"]):
        if abs(nested["time"] - reference["time"]) > 1e-12:
            check(False, f"the steps' times differ: {nested['time']} and {reference['time']}")
            break
        scale = 10 * LOOP_TOLERANCE * reference["normal_force_N"]
        for force in ("normal_force_N", "tangential_force_N"):
            difference = abs(nested[force] - reference[force])
            check(difference <= scale, f"t = {nested['time']:g}: {force} {nested[force]:.6g} against "
                  f"{reference[force]:.6g} (difference {difference:.3g} <= {scale:.3g})")
check.finish()
