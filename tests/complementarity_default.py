#!/usr/bin/python3
"""The default `Contact/Complementarity = automatic` (doc/formulation.md, "Which
conditions by default"): between two deformable bodies the answer does not
depend on the augmentation parameter r_n.

prm/patin_deformable_block.prm (the patin on a deformable block, non-matching
meshes, Coulomb mu = 0.1, 10 load steps) with the defaults and `Automatic r_n
factor` 0.01 and 100:
- the log names the choice ("Complementarity = automatic: weighted (two
  deformable bodies)") and run_summary.csv records it (weighted_complementarity = 1);
- the nodal contact pressures of every load step differ by less than a tenth of
  the mesh's own pressure error, the smallest estimated_pressure_error of the
  load steps (the relative L2 error of the pressure that the error estimator gives,
  doc/formulation.md "Error estimate"), against the peak pressure: a parameter that
  moves the answer by less than that is below what the mesh resolves. The
  weighted conditions are r_n-independent to the Newton tolerance (1e-13 of the
  peak with the nested loops);
- the same sweep with `Complementarity = pointwise` (the default until issue 49,
  the seed's formulation) moves the pressures by more than that bound (1.9 x the
  peak at the patin's corners): the check can fail.
Also: against a rigid obstacle (prm/patin_elastic.prm) the default stays
pointwise and says so."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
scene = sltest.read_prm(os.path.join(prm_dir, "patin_deformable_block.prm"))
FACTORS = (0.01, 100)
# below a tenth of the discretisation error, a parameter's effect is negligible
FRACTION_OF_DISCRETISATION_ERROR = 0.1


def profiles(out):
    """Every load step's profile: the nodes of the slave's contact surface."""
    folder = os.path.join(out, "output")
    names = sorted(p for p in os.listdir(folder) if p.startswith("profile-"))
    return [sltest.read_csv(os.path.join(folder, name)) for name in names]


def run(name, text):
    out = os.path.join(workdir, name)
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
        return None
    output = os.path.join(out, "output")
    return {"log": log, "profiles": profiles(out),
            "statistics": sltest.read_csv(os.path.join(output, "statistics.csv")),
            "summary": sltest.read_csv(os.path.join(output, "run_summary.csv"))[0]}


def largest_difference(a, b):
    """max over the steps and nodes of |p_a - p_b| against the largest |p| of a."""
    if len(a) != len(b) or any(len(sa) != len(sb) for sa, sb in zip(a, b)):
        return float("inf")
    peak = max(abs(row["contact_pressure_MPa"]) for step in a for row in step)
    difference = 0.
    for step_a, step_b in zip(a, b):
        for row_a, row_b in zip(step_a, step_b):
            if abs(row_a["x_mm"] - row_b["x_mm"]) > 1e-9:
                return float("inf")
            difference = max(difference, abs(row_a["contact_pressure_MPa"] - row_b["contact_pressure_MPa"]))
    return difference / peak


def sweep(label, complementarity):
    extra = sltest.nested_set("Contact/Complementarity", complementarity) if complementarity else ""
    return {f: run(f"{label}-{f}", scene + sltest.nested_set("Contact/Automatic r_n factor", f) + extra)
            for f in FACTORS}


default = sweep("default", None)
bound = None
if all(default.values()):
    for factor, result in default.items():
        check("Complementarity = automatic: weighted (two deformable bodies)" in result["log"],
              f"default, r_n factor {factor}: the log names the choice")
        check(result["summary"].get("weighted_complementarity") == 1.,
              f"default, r_n factor {factor}: run_summary.csv has weighted_complementarity = "
              f"{result['summary'].get('weighted_complementarity')}")
    error = min(min(row["estimated_pressure_error"] for row in r["statistics"]) for r in default.values())
    bound = FRACTION_OF_DISCRETISATION_ERROR * error
    difference = largest_difference(default[FACTORS[0]]["profiles"], default[FACTORS[1]]["profiles"])
    check(difference < bound, f"default, r_n factor {FACTORS[0]} against {FACTORS[1]}: the nodal "
          f"pressures differ by {difference:.1e} of the peak (bound {bound:.1e}: "
          f"{FRACTION_OF_DISCRETISATION_ERROR:g} x the estimated pressure error {error:.3f})")

pointwise = sweep("pointwise", "pointwise")
if bound is not None and all(pointwise.values()):
    difference = largest_difference(pointwise[FACTORS[0]]["profiles"], pointwise[FACTORS[1]]["profiles"])
    check(difference > bound, f"Complementarity = pointwise, r_n factor {FACTORS[0]} against "
          f"{FACTORS[1]}: the nodal pressures move by {difference:.1e} of the peak (> {bound:.1e}: "
          f"the r_n dependence the default removes)")

rigid = run("rigid", sltest.read_prm(os.path.join(prm_dir, "patin_elastic.prm")) +
            sltest.nested_set("Load stepping/Number of load steps", 1) +
            sltest.nested_set("Load stepping/End time", 0.1))
if rigid is not None:
    check("Complementarity = automatic: pointwise (a rigid obstacle" in rigid["log"] and
          rigid["summary"].get("weighted_complementarity") == 0.,
          "rigid obstacle: the default stays pointwise, named in the log and run_summary.csv")
check.finish()
