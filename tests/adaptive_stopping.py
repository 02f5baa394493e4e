#!/usr/bin/python3
"""Adaptive stopping of the nested loops and of Newton (`Nonlinear
solver/Stopping = adaptive`, doc/formulation.md, "Adaptive stopping").

On the neo-Hookean patin, whose coarse mesh carries a large estimated
discretisation error (about the solution's energy), with the default
`Adaptive stopping fraction` (0.02):
- adaptive stopping takes fewer Newton iterations than the fixed tolerances
  (measured 82 against 132), and fewer friction iterations: the outer loops
  stop early too, and statistics.csv counts the early stops (adaptive_stops);
- the result stays within the stated fraction of the estimate: the contact
  pressure of every load step differs from the fixed run's by less than the
  fraction times the estimated relative error, relative to the largest
  pressure;
- on 2 MPI ranks the loops stop where they stop on one (the estimate and the
  changes are collective): the same Newton and friction iterations in every
  step;
- in 3D (prm/patin_3d.prm) too: fewer Newton iterations (measured 66 against
  144), and the normal and tangential forces of every step within the
  fraction times the estimated relative error of the fixed run's."""
import os
import sys
import sltest

FRACTION = 0.02  # the default of `Adaptive stopping fraction`

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
patin = sltest.read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                                     "patin_neo_hookean.prm"))


def stopping(scene, mode):
    """The scene's text with `Stopping = mode`."""
    return scene + f"""
subsection Nonlinear solver
  set Stopping = {mode}
end
"""


runs = {}
for mode in ("fixed", "adaptive"):
    out = os.path.join(workdir, mode)
    if sltest.run_checked(executable, stopping(patin, mode), out, check, f"neo-Hookean patin, Stopping = {mode}"):
        output = os.path.join(out, "output")
        profiles = sorted(p for p in os.listdir(output) if p.startswith("profile-"))
        runs[mode] = (sltest.read_csv(os.path.join(output, "run_summary.csv"))[0],
                      sltest.read_csv(os.path.join(output, "statistics.csv")),
                      [sltest.read_csv(os.path.join(output, p)) for p in profiles])
if len(runs) == 2:
    (fixed, fixed_steps, fixed_profiles), (adaptive, adaptive_steps, adaptive_profiles) = \
        runs["fixed"], runs["adaptive"]
    check(adaptive["newton_iterations"] < fixed["newton_iterations"],
          f"adaptive stopping: {adaptive['newton_iterations']:.0f} Newton iterations against "
          f"{fixed['newton_iterations']:.0f} with the fixed tolerances")
    friction = [sum(s["friction_iterations"] for s in steps) for steps in (fixed_steps, adaptive_steps)]
    stops = [sum(s["adaptive_stops"] for s in steps) for steps in (fixed_steps, adaptive_steps)]
    check(friction[1] < friction[0] and stops[0] == 0 and stops[1] > 0,
          f"the friction loop stops early too: {friction[1]:.0f} friction iterations against "
          f"{friction[0]:.0f}; early stops counted in statistics.csv: {stops[1]:.0f} (fixed: {stops[0]:.0f})")
    largest = max(abs(r["contact_pressure_MPa"]) for p in fixed_profiles for r in p)
    difference = max(abs(a["contact_pressure_MPa"] - b["contact_pressure_MPa"])
                     for p, q in zip(fixed_profiles, adaptive_profiles) for a, b in zip(p, q))
    bound = FRACTION * fixed["estimated_relative_error"]
    check(len(fixed_profiles) == len(adaptive_profiles) and difference / largest < bound,
          f"the pressure differs by {difference / largest:.1e} of the largest, below {FRACTION} x the "
          f"estimated relative error ({bound:.4f})")

# 2 ranks: the same stops
out = os.path.join(workdir, "adaptive-np2")
code, log = sltest.run(executable, stopping(patin, "adaptive") + sltest.QUIET_OUTPUT, out, ranks=2,
                       expect_success=False)
check(code == 0, f"neo-Hookean patin, Stopping = adaptive, 2 ranks: exit code {code}")
if code != 0:
    print(log[-2000:])
elif "adaptive" in runs:
    parallel = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    columns = ("newton_iterations", "friction_iterations", "status_iterations", "adaptive_stops")
    same = len(parallel) == len(runs["adaptive"][1]) and all(
        a[c] == b[c] for a, b in zip(runs["adaptive"][1], parallel) for c in columns)
    check(same, "2 ranks: the same Newton, friction and status iterations and early stops in every step as "
                f"1 rank ({sum(r['newton_iterations'] for r in parallel):.0f} Newton iterations against "
                f"{adaptive['newton_iterations']:.0f})")

# 3D: the 3D patin as shipped
patin_3d = sltest.read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm", "patin_3d.prm"))
steps = {}
for mode in ("fixed", "adaptive"):
    out = os.path.join(workdir, f"patin3d-{mode}")
    if sltest.run_checked(executable, stopping(patin_3d, mode), out, check, f"3D patin, Stopping = {mode}"):
        steps[mode] = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
if len(steps) == 2:
    fixed_3d, adaptive_3d = steps["fixed"], steps["adaptive"]
    iterations = [sum(r["newton_iterations"] for r in rows) for rows in (fixed_3d, adaptive_3d)]
    check(iterations[1] < iterations[0],
          f"3D patin: {iterations[1]:.0f} Newton iterations against {iterations[0]:.0f} with the fixed tolerances")
    bound = FRACTION * fixed_3d[-1]["estimated_relative_error"]
    worst = max(abs(a[c] - b[c]) / abs(a["normal_force_N"])
                for a, b in zip(fixed_3d, adaptive_3d) for c in ("normal_force_N", "tangential_force_N"))
    check(len(fixed_3d) == len(adaptive_3d) and worst < bound,
          f"3D patin: the forces differ by {worst:.1e} of the normal force, below {FRACTION} x the estimated "
          f"relative error ({bound:.4f})")
check.finish()
