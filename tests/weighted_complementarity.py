#!/usr/bin/python3
"""`Contact/Complementarity = weighted`: the contact and friction conditions per
multiplier node on the weighted gap and slip (doc/formulation.md, "Weighted
complementarity"), whose discrete solution does not depend on r_n.

- prm/patin_deformable_block.prm (the patin on a deformable block, non-matching
  meshes, Coulomb mu = 0.1) with `Automatic r_n factor` 0.01, 1 and 100, with
  the nested loops and with the generalized Newton: the nodal pressures of
  every load step agree to 1e-8 of the peak (the exact discrete solution is
  the same; Newton's tolerance is 1e-10 so that it is resolved below that), and in the last step, where every node
  slips, |t_j| = mu lambda_j at every node (to 1e-8 with the threshold
  linearised, to the friction loop's 1e-4 with it iterated). The same on 2
  MPI ranks.
- The pointwise conditions on the same scene with factor 100: the pressures
  move by more than 1 % of the peak (what the weighted conditions remove;
  the check shows this test can tell).
- prm/two_cylinders.prm (curved non-matching interface, stick and slip
  zones) with factors 0.01 and 100 against 1: nodal pressures to 1e-8 of the peak.
- The rigid obstacle (prm/patin_elastic.prm with Gauss contact quadrature,
  whose points are not the multiplier nodes): factors 0.01 and 100 against 1.
- The weighted conditions refuse hanging multiplier nodes on the contact
  surface (3D local refinement) with a message naming the entry."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
TOLERANCE = 1e-8


# the discrete solutions are compared to 1e-8: Newton resolves them to 1e-10
# (with its quadratic end, the default 1e-8 leaves ~1e-7 in the pressures)
NEWTON = sltest.nested_set("Nonlinear solver/Newton/Tolerance", 1e-10)


def variant(factor, mode="weighted", extra=""):
    return (sltest.nested_set("Contact/Automatic r_n factor", factor) +
            sltest.nested_set("Contact/Complementarity", mode) + NEWTON + extra)


def profiles(out):
    """Every step's profile: the nodes of the slave's contact surface."""
    folder = os.path.join(out, "output")
    names = sorted(p for p in os.listdir(folder) if p.startswith("profile-"))
    return [sltest.read_csv(os.path.join(folder, name)) for name in names]


def run(scene, name, text, ranks=1):
    out = os.path.join(workdir, name)
    code, log = sltest.run(executable, scene + text + sltest.QUIET_OUTPUT, out, ranks=ranks,
                           expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
        return None
    return profiles(out), sltest.read_csv(os.path.join(out, "output", "statistics.csv"))


def largest_difference(a, b):
    """max over the steps and nodes of |p_a - p_b| against the largest |p|, and that peak."""
    if len(a) != len(b):
        return float("inf"), 0.
    peak = max(abs(row["contact_pressure_MPa"]) for step in a for row in step)
    difference = 0.
    for step_a, step_b in zip(a, b):
        if len(step_a) != len(step_b):
            return float("inf"), peak
        for row_a, row_b in zip(step_a, step_b):
            if abs(row_a["x_mm"] - row_b["x_mm"]) > 1e-9:
                return float("inf"), peak
            difference = max(difference, abs(row_a["contact_pressure_MPa"] - row_b["contact_pressure_MPa"]))
    return difference / peak, peak


def compare_factors(scene, label, factors, extra="", ranks=1, reference=None):
    results = {f: run(scene, f"{label}-{f}", variant(f, extra=extra), ranks) for f in factors}
    base = reference or results.get(1)
    for factor, result in results.items():
        if result is None or base is None or result is base:
            continue
        difference, peak = largest_difference(base[0], result[0])
        check(difference <= TOLERANCE, f"{label}, r_n factor {factor} against 1: nodal pressures "
              f"agree to {difference:.1e} of the peak {peak:.1f} MPa (bound {TOLERANCE:g})")
    return results


deformable = sltest.read_prm(os.path.join(prm_dir, "patin_deformable_block.prm"))
mu = 0.1
for algorithm, extra in (("nested", ""), ("generalized Newton", sltest.GENERALIZED_NEWTON)):
    results = compare_factors(deformable, f"patin on block, {algorithm}", (0.01, 1, 100), extra)
    for factor, result in results.items():
        if result is None:
            continue
        last, nodes = result[1][-1], result[0][-1]
        if last["points_stick"] != 0 or last["points_in_contact"] == 0:
            check(False, f"patin on block, {algorithm}, factor {factor}: every node slips in the "
                  f"last step ({last['points_stick']:.0f} stick)")
            continue
        # Coulomb's law per node, |t_j| = s_j = mu lambda_j: exact where the
        # threshold is linearised (generalized Newton), to the friction loop's
        # tolerance on s where it is a fixed point (nested)
        bound = TOLERANCE if extra else 1e-4
        peak = max(row["contact_pressure_MPa"] for row in nodes)
        error = max(abs((row["tangential_traction_x_MPa"] ** 2 + row["tangential_traction_y_MPa"] ** 2) ** 0.5
                        - mu * row["contact_pressure_MPa"]) for row in nodes) / (mu * peak)
        check(error <= bound, f"patin on block, {algorithm}, factor {factor}: all "
              f"{last['points_slip']:.0f} nodes slip, |t_j| = mu lambda_j to {error:.1e} of mu p_max "
              f"(bound {bound:g})")
        # the totals: F_t is the norm of the vector sum over a surface that
        # turns a little as the block deforms, so below mu F_n by the cosine
        # of that turn; against the pointwise conditions' 5 % (factor 100)
        ratio = last["tangential_force_N"] / last["normal_force_N"]
        check(abs(ratio - mu) <= 1e-5 * mu, f"patin on block, {algorithm}, factor {factor}: "
              f"F_t / F_n = {ratio:.9f} (mu = {mu:g}, bound 1e-5 relative)")
    if algorithm == "nested" and results[1] is not None:
        parallel = run(deformable, "patin on block, nested, 2 ranks", variant(1), ranks=2)
        if parallel is not None:
            difference, _ = largest_difference(results[1][0], parallel[0])
            check(difference <= TOLERANCE, f"patin on block, 2 ranks against 1: nodal pressures "
                  f"agree to {difference:.1e} of the peak")
        pointwise = run(deformable, "patin on block, pointwise, factor 100", variant(100, "pointwise"))
        if pointwise is not None:
            last = pointwise[1][-1]
            ratio = last["tangential_force_N"] / last["normal_force_N"]
            print(f"      (pointwise, factor 100: F_t / F_n = {ratio:.4f} with {last['points_slip']:.0f} "
                  f"of {last['points_in_contact']:.0f} points slipping)")
        pointwise_1 = run(deformable, "patin on block, pointwise, factor 1", variant(1, "pointwise"))
        if pointwise is not None and pointwise_1 is not None:
            difference, _ = largest_difference(pointwise_1[0], pointwise[0])
            check(difference > 1e-2, f"pointwise conditions, factor 100 against 1: the pressures move "
                  f"by {difference:.1e} of the peak (> 1e-2: the r_n dependence the weighted ones remove)")

compare_factors(sltest.read_prm(os.path.join(prm_dir, "two_cylinders.prm")), "two cylinders",
                (0.01, 1, 100))
rigid = (sltest.read_prm(os.path.join(prm_dir, "patin_elastic.prm")) +
         sltest.nested_set("Contact/Contact quadrature", "Gauss"))
compare_factors(rigid, "patin on the rigid block, Gauss points", (0.01, 1, 100))

# hanging nodes on the contact surface (3D: the locally refined half ball): refused, naming the entry
sphere = (sltest.read_prm(os.path.join(prm_dir, "hertz_sphere.prm")) +
          sltest.nested_set("Geometry/half ball/Radius", 50) +
          sltest.nested_set("Geometry/half ball/Local refinement radius", 15) +
          sltest.nested_set("Geometry/half ball/Contact zone radius", 14))
code, log = sltest.run(executable, sphere + variant(1) + sltest.QUIET_OUTPUT,
                       os.path.join(workdir, "hanging"), expect_success=False)
check(code != 0 and "Complementarity = weighted" in log and "hanging" in log,
      f"hanging multiplier nodes refused (exit code {code}), the message naming the entry")
check.finish()
