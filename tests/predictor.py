#!/usr/bin/python3
"""`Nonlinear solver/Predictor = extrapolation`: a load step starts from the last
converged state plus the last step's change of every unknown, scaled to the step.

1. The contact patch test (prm/contact_patch_test.prm, linear: elastic bodies,
   frictionless, a pressure ramped linearly over 4 steps, the contact set fixed):
   the solution is linear in t, so the extrapolated state of steps 2-4 is the
   solution itself and must pass the Newton criterion with no iteration, where
   the tangent start takes one per step; the normal force must be p L t in
   every step, both ways, to the Newton tolerance (1e-8 scaled; 1e-7 here).
2. The patin on a deformable block (prm/patin_deformable_block.prm, Coulomb
   friction, non-matching meshes, 10 steps): both starts must give the same
   forces in every step (to 1e-6 of the largest, the Newton criterion's
   reach) and the extrapolation fewer Newton iterations in all (measured
   87 against 135).
"""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))


def steps_of(text, name, predictor):
    out = os.path.join(workdir, f"{name}_{predictor}")
    if not sltest.run_checked(executable, text + sltest.nested_set("Nonlinear solver/Predictor", predictor),
                              out, check, f"{name}, {predictor}"):
        return None
    return sltest.read_csv(os.path.join(out, "output", "statistics.csv"))


# 1. a linear load path
patch = sltest.read_prm(os.path.join(prm_dir, "contact_patch_test.prm"))
STEPS = "set Number of load steps = 2"
if STEPS not in patch:
    raise SystemExit(f"FAIL: prm/contact_patch_test.prm has no '{STEPS}'")
patch = patch.replace(STEPS, "set Number of load steps = 4")
runs = {p: steps_of(patch, "patch test", p) for p in ("tangent", "extrapolation")}
if all(runs.values()):
    tangent, extrapolated = runs["tangent"], runs["extrapolation"]
    check(len(tangent) == len(extrapolated) == 4, "patch test: 4 steps both ways")
    iterations = [int(row["newton_iterations"]) for row in extrapolated]
    check(iterations[0] >= 1 and iterations[1:] == [0, 0, 0],
          f"patch test: the extrapolated steps 2-4 need no Newton iteration (per step: {iterations}; "
          f"tangent: {[int(row['newton_iterations']) for row in tangent]})")
    for a, b in zip(tangent, extrapolated):
        exact = 1000. * a["time"]
        check(abs(a["normal_force_N_per_mm"] - exact) <= 1e-7 * exact and
              abs(b["normal_force_N_per_mm"] - exact) <= 1e-7 * exact,
              f"patch test, t = {a['time']}: F_n {a['normal_force_N_per_mm']:.10g} (tangent) and "
              f"{b['normal_force_N_per_mm']:.10g} (extrapolation) against p L t = {exact:.10g} N/mm")

# 2. friction between two bodies
block = sltest.read_prm(os.path.join(prm_dir, "patin_deformable_block.prm"))
runs = {p: steps_of(block, "patin on a block", p) for p in ("tangent", "extrapolation")}
if all(runs.values()):
    tangent, extrapolated = runs["tangent"], runs["extrapolation"]
    check(len(tangent) == len(extrapolated), f"patin on a block: {len(tangent)} steps both ways")
    largest = max(abs(row[k]) for row in tangent
                  for k in ("normal_force_N_per_mm", "tangential_force_N_per_mm"))
    gap = max(abs(a[k] - b[k]) for a, b in zip(tangent, extrapolated)
              for k in ("normal_force_N_per_mm", "tangential_force_N_per_mm"))
    check(gap <= 1e-6 * largest,
          f"patin on a block: forces of every step agree to {gap / largest:.2e} of the largest")
    n_tangent = sum(int(row["newton_iterations"]) + int(row["failed_attempt_newton_iterations"])
                    for row in tangent)
    n_extrapolated = sum(int(row["newton_iterations"]) + int(row["failed_attempt_newton_iterations"])
                         for row in extrapolated)
    check(n_extrapolated < n_tangent,
          f"patin on a block: {n_extrapolated} Newton iterations extrapolating, {n_tangent} from the "
          f"tangent start")

check.finish()
