#!/usr/bin/python3
"""The stick-zone tangential traction of a nearly incompressible Hertz cylinder is smooth with the
recommended pair, and the pair that makes it alternate from node to node is named in a warning
(doc/near_incompressibility.md, "Stick-zone traction").

prm/hertz_cylinder.prm with Coulomb mu = 0.3, nu = 0.4999, Volumetric formulation = F-bar, the
top face moved down by 1.5 mm in 2 load steps (x held): the exact frictional traction of an
incompressible body on a rigid plane vanishes (Dundurs' beta = (1 - 2 nu)/(2 (1 - nu)) = 2e-4),
so what the stick zone carries is the body's own (the held top, the load path), smooth on the
scale of the contact half-width a.

The measure: along the stick nodes (the outermost on each side left out: it meets the slip zone's
kink, and so are the values next to it), the second differences d2_i = t_{i-1} - 2 t_i + t_{i+1} of the tangential traction; where
two neighbouring d2 have opposite signs (a node-to-node alternation), the smaller magnitude is the
alternation there; the largest, over the peak pressure p0. A smooth traction bounded by mu p0 and
rising over a, like mu p0 (x/a)^2, has d2 = 2 mu p0 (h/a)^2 (h the node spacing): the bound.

- Q1/P1 coarse with F-bar (one multiplier per two contact faces): below the bound, no warning;
- Q1/P1 with F-bar (a multiplier at every contact node takes up the checkerboard mode of the
  Q1/P0 mean dilatation): the warning, naming the pair and the remedy, and the alternation above
  the bound (so the measure sees the mode);
- nu = 0.3 with the displacement formulation: no warning."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
MU = 0.3
base = sltest.read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                                    "hertz_cylinder.prm")) + "".join(
    sltest.nested_set(path, value) for path, value in (
        ("Contact/Friction law/Coulomb/Friction coefficient", MU),
        ("Boundary conditions/Dirichlet 1/Components", "x, y"),
        ("Boundary conditions/Dirichlet 1/Displacement/Function expression", "0; -delta*t"),
        ("Boundary conditions/Dirichlet 1/Displacement/Function constants", "delta=1.5"),
        ("Load stepping/Number of load steps", 2)))
WARNING = "the stick-zone tangential traction alternates from node to node"


def alternation(rows):
    """(largest alternation / p0, its bound 2 mu (h/a)^2, stick nodes) of a profile."""
    rows = sorted(rows, key=lambda r: r["x_mm"])
    stick = {i for i, r in enumerate(rows) if r["status"] == 1}
    inner = {i for i in stick if i - 1 in stick and i + 1 in stick}
    t = [r["tangential_traction_x_MPa"] for r in rows]
    d2 = {i: t[i - 1] - 2 * t[i] + t[i + 1] for i in inner if i - 1 in inner and i + 1 in inner}
    alternating = [min(abs(d2[i]), abs(d2[i + 1])) for i in d2 if i + 1 in d2 and d2[i] * d2[i + 1] < 0]
    p0 = max(r["contact_pressure_MPa"] for r in rows)
    touching = [r["x_mm"] for r in rows if r["status"] > 0]
    a = 0.5 * (max(touching) - min(touching))
    h = min(rows[i + 1]["x_mm"] - rows[i]["x_mm"] for i in range(len(rows) - 1) if i in stick)
    return max(alternating, default=0.) / p0, 2 * MU * (h / a) ** 2, len(stick)


for name, nu, formulation, pair, smooth in (
        ("Q1-P1-coarse_F-bar", 0.4999, "F-bar", "Q1/P1 coarse", True),
        ("Q1-P1_F-bar", 0.4999, "F-bar", "Q1/P1", False),
        ("Q1-P1_nu0.3", 0.3, "displacement", "Q1/P1", None)):
    text = base + sltest.nested_set("Material/linear elastic/Poisson's ratio", nu) + \
        sltest.nested_set("Material/Volumetric formulation", formulation) + \
        sltest.nested_set("Contact/Finite element pair", pair)
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, f"{workdir}/{name}",
                           expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
        continue
    warned = WARNING in log
    check(warned == (smooth is False) and (not warned or ("Q1/P1 coarse" in log and "mixed" in log)),
          f"{name}: stick-zone warning {'given, naming Q1/P1 coarse and mixed' if smooth is False else 'absent'}"
          f" ({warned})")
    if smooth is None:
        continue
    measured, bound, n_stick = alternation(sltest.last_profile(f"{workdir}/{name}/output"))
    check(n_stick >= 10, f"{name}: {n_stick} stick nodes (at least 10 to measure along)")
    check((measured < bound) == smooth,
          f"{name}: node-to-node alternation of the stick traction {measured:.4f} p0 "
          f"{'<' if smooth else '>'} 2 mu (h/a)^2 = {bound:.4f}")
check.finish()
