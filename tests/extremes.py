#!/usr/bin/python3
"""Numerical stability at the extremes: every run ends converged or with a clean
non-convergence message, never a crash, a hang or a NaN in an output file.

On the elastic patin (coarse mesh), with the nested loops and with the full
generalized Newton:
- r_n and r_t from 1e-6 to 1e12 times their automatic values (both, and each
  extreme against the other);
- friction coefficients 0, 0.01, 1 and 10;
- Poisson's ratios 0.49 and 0.4999 (nearly incompressible);
- a very coarse (2 contact faces) and a very fine (128 contact faces) mesh;
and the neo-Hookean patin at the extreme parameter factors.

Checks per run: exit code 0, or 2 with the program's non-convergence message;
finished within the time limit; no NaN or inf in any CSV or .vtu file. Runs
that converge must also be right: the stabilized Lagrangian's solution does
not depend on r_n and r_t, so the contact forces equal those of the automatic
parameters (to 1e-6 relative, from the solver tolerances), and the friction
force never exceeds μ times the normal force."""
import os
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
TIME_LIMIT = 300  # seconds per run; the slowest converging run takes about 3 s

def patin(name, refinements=2):
    with open(os.path.join(root, "prm", f"patin_{name}.prm")) as f:
        text = f.read()
    return (text + sltest.nested_set("Geometry/block/Global refinements", refinements) +
            sltest.nested_set("Contact/r_n", "automatic") + sltest.nested_set("Contact/r_t", "automatic"))


def factors(fn, ft):
    return (sltest.nested_set("Contact/Automatic r_n factor", fn) +
            sltest.nested_set("Contact/Automatic r_t factor", ft))


cases = []  # (name, prm text, reference case name or None, friction coefficient)
for material in ("elastic", "neo_hookean"):
    cases.append((f"{material} automatic", patin(material), None, 0.1))
    for fn, ft in ((1e-6, 1e-6), (1e12, 1e12), (1e-6, 1e12), (1e12, 1e-6)):
        cases.append((f"{material} r_n x {fn:g}, r_t x {ft:g}", patin(material) + factors(fn, ft),
                      f"{material} automatic", 0.1))
for mu in (0, 0.01, 1, 10):
    cases.append((f"mu = {mu}", patin("elastic") +
                  sltest.nested_set("Contact/Friction law/Coulomb/Friction coefficient", mu), None, mu))
for nu in (0.49, 0.4999):
    cases.append((f"nu = {nu}", patin("elastic") +
                  sltest.nested_set("Material/linear elastic/Poisson's ratio", nu), None, 0.1))
cases.append(("very coarse mesh", patin("elastic", 0), None, 0.1))
cases.append(("very fine mesh", patin("elastic", 6), None, 0.1))

summaries = {}
for algorithm, extra in (("nested", ""), ("newton", sltest.GENERALIZED_NEWTON)):
    for name, text, reference, mu in cases:
        label = f"{name}, {algorithm}"
        out = os.path.join(workdir, algorithm, name.replace(" ", "_").replace(",", ""))
        shutil.rmtree(out, ignore_errors=True)
        prm = text + extra + "\nsubsection Output\n  set Output directory = output\nend\n"
        try:
            code, log = sltest.run(executable, prm, out, expect_success=False, timeout=TIME_LIMIT)
        except subprocess.TimeoutExpired:
            check(False, f"{label}: still running after {TIME_LIMIT} s")
            continue
        clean = code == 0 or (code == 2 and "did not converge" in log)
        check(clean, f"{label}: exit code {code}" + ("" if code else ", converged") +
              (", non-convergence reported" if code == 2 and clean else ""))
        if not clean:
            print(log[-2000:])
        csvs = [os.path.join(d, f) for d, _, fs in os.walk(out) for f in fs if f.endswith(".csv")]
        bad = [f for f in csvs if any(token in open(f).read().lower() for token in ("nan", "inf"))]
        check(not bad, f"{label}: no NaN or inf in {len(csvs)} CSV files" +
              (f" (found in {', '.join(bad)})" if bad else ""))
        if code != 0:
            continue
        last = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]
        summaries[label] = last
        fn, ft = last["normal_force_N"], last["tangential_force_N"]
        check(fn > 0 and ft <= mu * fn * (1 + 1e-8) + 1e-9,
              f"{label}: F_n = {fn:.6g} N > 0, F_t = {ft:.6g} N <= mu F_n")
        ref = summaries.get(f"{reference}, {algorithm}") if reference else None
        if ref:
            difference = max(abs(last[k] - ref[k]) for k in ("normal_force_N", "tangential_force_N"))
            check(difference <= 1e-6 * ref["normal_force_N"],
                  f"{label}: forces as with the automatic r_n, r_t (difference {difference:.2e} N)")

pvpython = shutil.which("pvpython")
check(pvpython is not None, "pvpython is installed (package python3-paraview)")
if pvpython:
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_finite_vtu.py")
    result = subprocess.run([pvpython, script, workdir], capture_output=True, text=True)
    print(result.stdout.strip()[-3000:])
    check(result.returncode == 0, "every .vtu file is finite")
check.finish()
