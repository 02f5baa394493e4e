#!/usr/bin/python3
"""`Adaptive refinement/Target pressure error` (doc/error_estimator.md,
"Accuracy targets"): the cycles stop with the true pressure error below the
target, at most one cycle after it first is.

The true error is the relative L2 error of the last load step's contact
pressure against Hertz's closed form with the run's own force
(contrib/hertz_errors.py), read from each cycle's profile. Checks, with
`Criterion = estimator`:
- the Hertz cylinder with 0.05 mm of indentation (a/R = 0.014: the half-space
  closed form holds to about 2e-4) from a coarse mesh, target 0.042: the
  cycle where the estimate first falls below the target (0.040 against a
  true error of 0.043) is not where a bound of the error is: the run says
  "met", the true error of its last cycle is below the target, that of two
  cycles before is not;
- prm/hertz_cylinder.prm as shipped, target 0.01: the same (its true error
  holds the closed form's own, of order (a/R)^2 = 0.01 at a/R = 0.1: it
  floors near 0.009 while the estimate goes on falling);
- every cycle adds multiplier DoFs (the contact zone is refined).
"""
import os
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
from hertz_errors import hertz_scene  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")

# the mesh of sltest.coarse_hertz(), the indentation in one step
shallow = hertz_scene(2, "Q1/P1", 2, 0.05) + """
subsection Geometry
  subsection half ball
    set Global refinements = 2
  end
end
"""
shipped = sltest.read_prm(os.path.join(ROOT, "prm", "hertz_cylinder.prm"))


for name, scene, target in (("shallow Hertz", shallow, 0.042), ("prm/hertz_cylinder.prm", shipped, 0.01)):
    out = os.path.join(workdir, name.replace(" ", "_").replace("/", "_"))
    text = scene.replace("output-hertz-cylinder", "output") + f"""
subsection Adaptive refinement
  set Cycles = 10
  set Criterion = estimator
  set Target pressure error = {target}
end
"""
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
        continue
    output = os.path.join(out, "output")
    rows = sltest.read_csv(os.path.join(output, "refinement_cycles.csv"))
    errors = sltest.cycle_pressure_errors(output, rows)
    print(f"{name}, target {target}: cycle, DoFs, multiplier DoFs, estimate, true error")
    for row, error in zip(rows, errors):
        print(f"  {row['cycle']:.0f} {row['displacement_dofs']:.0f} {row['multiplier_dofs']:.0f} "
              f"{row['estimated_pressure_error']:.4f} {error:.4f}")
    check("Accuracy target met" in log, f"{name}: the run says the target is met")
    check(errors[-1] < target, f"{name}: the last cycle's true error {errors[-1]:.4f} is below the target {target}")
    check(len(errors) < 3 or errors[-3] >= target,
          f"{name}: two cycles before the last the true error was not yet below the target "
          f"({', '.join(f'{e:.4f}' for e in errors)})")
    mult = [row["multiplier_dofs"] for row in rows]
    check(all(b > a for a, b in zip(mult, mult[1:])),
          f"{name}: every cycle adds multiplier DoFs: {', '.join(f'{m:.0f}' for m in mult)}")

check.finish()
