#!/usr/bin/python3
"""The same scene on 1 and on 6 or 8 MPI ranks (oversubscribed): the 3D Hertz sphere
(prm/hertz_sphere.prm at Global refinements 1: 1168 cells, three levels of local refinement
under the contact zone), with the direct and the iterative linear solver.

Every rank must agree on which faces are on the contact boundary. The half ball closes its
contact zone over the children of refined faces (one child in it puts all in it), which a
rank decides from its own and its ghost cells; before the owners' boundary ids were given to
the ghost cells (ContactProblem::share_ghost_boundary_ids), a rank whose ghost face was
joined to the zone by a cell it cannot see counted different multiplier DoFs: on 6 ranks 84
(later 78) instead of 81, and MUMPS found the system singular, GMRES failed with a Trilinos
error. Checks: the same displacement and multiplier DoFs, the same Newton iterations, and
the contact force equal to 1e-8 (the Newton tolerance's order; the runs differ by the order
of sums and, with GMRES, by its partition-dependent AMG)."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm")
scene = sltest.read_prm(os.path.join(prm_dir, "hertz_sphere.prm"))
assert "set Global refinements      = 2" in scene
scene = scene.replace("set Global refinements      = 2", "set Global refinements      = 1")


def run(name, text, ranks):
    out = os.path.join(workdir, name)
    if not sltest.run_checked(executable, text, out, check, name, ranks=ranks):
        return None
    output = os.path.join(out, "output")
    return (sltest.read_csv(os.path.join(output, "run_summary.csv"))[0],
            sltest.read_csv(os.path.join(output, "statistics.csv"))[-1])


for solver in ("direct", "iterative"):
    text = scene + sltest.nested_set("Linear solver/Method", solver)
    reference = run(f"{solver}-1", text, 1)
    for ranks in (6, 8):
        result = run(f"{solver}-{ranks}", text, ranks)
        if reference is None or result is None:
            continue
        (summary, last), (summary_1, last_1) = result, reference
        check(all(summary[c] == summary_1[c] for c in ("displacement_dofs", "multiplier_dofs", "newton_iterations")),
              f"{solver}, {ranks} ranks: {summary['displacement_dofs']:.0f} + {summary['multiplier_dofs']:.0f} DoFs "
              f"and {summary['newton_iterations']:.0f} Newton iterations, as on one rank "
              f"({summary_1['displacement_dofs']:.0f} + {summary_1['multiplier_dofs']:.0f}, "
              f"{summary_1['newton_iterations']:.0f})")
        difference = abs(last["normal_force_N"] - last_1["normal_force_N"]) / abs(last_1["normal_force_N"])
        check(difference < 1e-8, f"{solver}, {ranks} ranks: the normal force {last['normal_force_N']:.10g} N "
              f"against {last_1['normal_force_N']:.10g} N on one rank ({difference:.1e})")
check.finish()
