#!/usr/bin/python3
"""What the solver does when a fixed point or the direct solver fails on a step.

- A fixed-point loop of the nest that does not converge in its iterations (or
  whose statuses repeat, a cycle) is folded into the generalized Newton for
  that step instead of failing it: the step converges without a cut, the log
  and statistics.csv (folded_loops) say so, and the forces are those of the
  run whose loops converged (the same discrete problem, to solver tolerance).
  Checked on the 2D Hertz cylinder (frictionless, status loop limited to 2
  iterations where it needs 4), on a pressed and slid block (friction loop
  limited to 2 iterations where it needs 6-7), and on a plate whose statuses
  cycle.
- MUMPS reporting a work space too small (INFOG(1) = -9, provoked with
  `Work space increase = 0` on the Q1/P2 pair, whose pivoting needs more than
  estimated): the log names the solver's error, the factorisation is redone
  with a larger work space, and the run converges."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
here = os.path.dirname(os.path.abspath(__file__))
hertz = sltest.read_prm(os.path.join(here, "..", "prm", "hertz_cylinder.prm"))
BLOCK = sltest.scene("friction_block")


def run(name, text):
    out = f"{workdir}/{name}"
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-2000:])
        return log, []
    return log, sltest.read_csv(out + "/output/statistics.csv")


for scene, text, loop, limit in (("hertz", hertz, "Status loop", 2),
                                  ("block", BLOCK, "Friction loop", 2)):
    _, reference = run(f"{scene}-default", text)
    log, limited = run(f"{scene}-limited",
                       text + sltest.nested_set(f"Nonlinear solver/{loop}/Maximum iterations", limit))
    needed = max(r[loop.split()[0].lower() + "_iterations"] for r in reference) if reference else 0
    check(needed > limit, f"{scene}: the {loop.lower()} needs {needed:.0f} iterations in a step "
                          f"without the limit of {limit}")
    word = {"Status loop": "the statuses are folded", "Friction loop": "the friction threshold is folded"}[loop]
    check(f"{loop.lower()}: no convergence in {limit} iterations" in log and word in log and
          "cutting the step" not in log,
          f"{scene}: the {loop.lower()} limited to {limit} iterations is folded into Newton, no step cut")
    if reference and limited:
        check(len(limited) == len(reference) and any(r["folded_loops"] > 0 for r in limited) and
              all(r["step_cuts"] == 0 for r in limited),
              f"{scene}: same steps, folded_loops counted in statistics.csv, no cuts")
        scale = max(r["normal_force_N"] for r in reference)
        for a, b in zip(reference, limited):
            for column in ("normal_force_N", "tangential_force_N"):
                # the friction loop stops at a relative threshold change of 1e-4
                check(abs(a[column] - b[column]) <= 1e-4 * scale,
                      f"{scene} step {a['step']:.0f} {column}: folded {b[column]:.6f} = "
                      f"converged loops {a[column]:.6f}")

# A real cycle: a thin plate pressed by a parabolic traction on part of its top,
# mu = 2 (tests/scenes/cycling_plate.prm): the statuses after the 4th status
# iteration of a friction iteration repeat those it started from. The cycle is
# detected, the statuses folded into Newton, and the step converges uncut to a
# state that satisfies the law it reports. (With mu = 2 Coulomb friction admits
# several solutions: the generalized Newton from the start finds another one,
# so no force is compared.)
log, stats = run("cycling-plate", sltest.scene("cycling_plate"))
check("(a cycle); the statuses are folded into the generalized Newton" in log,
      "cycling plate: the cycle of statuses is detected and named")
check(len(stats) == 1 and stats[0]["step_cuts"] == 0 and stats[0]["folded_loops"] >= 1 and
      stats[0]["friction_law_violations"] == 0 and "cutting the step" not in log,
      "cycling plate: the step converges without a cut, folded_loops counted, the law holds")

log, stats = run("q1p2-workspace",
                 BLOCK.replace("subsection Contact\n", "subsection Contact\n  set Finite element pair = Q1/P2\n") +
                 sltest.nested_set("Linear solver/Null pivot detection", "true") +
                 sltest.nested_set("Linear solver/Work space increase", 0))
check("MUMPS INFOG(1) = -9" in log and "factorised again with the work space increase" in log,
      "Q1/P2 with no work space margin: MUMPS's INFOG(1) = -9 named, factorised again")
check(len(stats) == 2 and all(r["step_cuts"] == 0 for r in stats), "Q1/P2: both steps converge without a cut")
check.finish()
