#!/usr/bin/python3
"""Symmetry planes on the built-in `half ball` (`Geometry/half ball/Symmetry planes = true`): only
x >= 0 (and y >= 0 in 3D) is meshed, and the planes x = 0 (id 4) and y = 0 (id 5) hold their
normal displacement. The Hertz cylinder (prm/hertz_cylinder.prm) as a half model and the Hertz
sphere (prm/hertz_sphere.prm) as a quarter model, pressed by the same displacement as the
scenes:

- the whole body's force is 2 (2D) or 4 (3D) times the model's, and a and p0 against Hertz with
  that force are within the bounds of tests/hertz.py (2D: |a - a_H| <= h/2 + 1 % a_H, the peak
  within 1 %) and of the sphere (3D: the peak within 3 %, a within h + 3 %);
- the whole force agrees with the full half-ball run's within 2 % (2D) and 3 % (3D): the two
  meshes differ (deal.II's quarter ball against its half ball), so this is their
  discretisation error, which the closed form bounds above;
- the model's faces on the symmetry planes are there: its mesh has ids 4 (and 5)."""
import os
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
from hertz_errors import hertz_errors  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")

for dim, scene, parts, bound in ((2, "hertz_cylinder.prm", 2, 0.02), (3, "hertz_sphere.prm", 4, 0.03)):
    text = sltest.read_prm(os.path.join(root, "prm", scene))
    results = {}
    for model, extra in (("whole", ""), ("symmetric", sltest.nested_set("Geometry/half ball/Symmetry planes", "true")
                                          + sltest.SYMMETRY_PLANES[dim])):
        out = os.path.join(workdir, f"{dim}d-{model}")
        sltest.run(executable, text + extra + sltest.QUIET_OUTPUT, out)
        force = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]["normal_force_N"]
        force *= parts if model == "symmetric" else 1
        results[model] = (force, hertz_errors(dim, force, sltest.last_profile(os.path.join(out, "output"))))
    force, errors = results["symmetric"]
    whole = results["whole"][0]
    check(abs(force - whole) <= bound * whole,
          f"{dim}D: {parts} x the model's force = {force:.1f} N, the whole body's {whole:.1f} N "
          f"({abs(force - whole) / whole:.2%})")
    h, a, a_h = errors["h_mm"], errors["a_mm"], errors["a_hertz_mm"]
    if dim == 2:
        ok = abs(a - a_h) <= 0.5 * h + 0.01 * a_h and errors["peak_error"] <= 0.01
    else:
        ok = abs(a - a_h) <= h + 0.03 * a_h and errors["peak_error"] <= 0.03
    whole_errors = results["whole"][1]
    check(ok, f"{dim}D symmetric: a = {a:.3f} mm (Hertz {a_h:.3f}, h = {h:.3f}), peak pressure error "
          f"{errors['peak_error']:.2%} (the whole body: a = {whole_errors['a_mm']:.3f}, "
          f"{whole_errors['peak_error']:.2%})")
check.finish()
