#!/usr/bin/python3
"""The reaction of each Dirichlet boundary (statistics.csv, `reaction_boundary_<id>_<x|y|z>_N`)
balances the contact force and the applied loads at every step: the reactions R_b (the force
each support exerts on the body), the contact force C on the body (`contact_force_*`, summed
over the contact points independently of the reactions) and the applied tractions F satisfy
sum_b R_b + C + F = 0, because the internal forces of a body sum to zero (the shape functions
are a partition of unity) and the residual at the free DoFs is at the solver's tolerance
(1e-10 of the forces here): the bound is 1e-8 of the largest reaction.

- prm/patin_elastic.prm (rigid plane, Dirichlet on the top face, pressed then slid) with the
  generalized Newton: both components. With the nested loops the normal component only: their
  tangential contact force is evaluated with the friction threshold of the last friction check,
  not that of the last Newton system, so it balances only to the friction loop's tolerance.
- prm/patin_elastoplastic.prm (J2, finite strain) with the generalized Newton.
- prm/patin_3d.prm (3D, one refinement fewer) with the generalized Newton: three components.
- prm/contact_patch_test.prm (two bodies, a pressure p = 100 t MPa on the upper body's 10 mm top
  face, three Dirichlet boundaries) on 2 MPI ranks: the contact forces
  between the bodies cancel, so the reactions sum to -F = (0, 1000 t) N/mm.
- prm/cook_membrane.prm (a shear traction 6.25 t MPa on the 16 mm right edge, clamped left
  edge, no contact): the reactions sum to (0, -100 t) N/mm."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
TOLERANCE = 1e-8


def rows_of(name, text, ranks=1):
    out = f"{workdir}/{name}"
    sltest.run(executable, text + sltest.QUIET_OUTPUT, out, ranks=ranks)
    rows = sltest.read_csv(out + "/output/statistics.csv")
    columns = [c for c in rows[0] if c.startswith("reaction_boundary_")]
    check(len(columns) > 0, f"{name}: statistics.csv has reaction columns ({', '.join(columns)})")
    return rows


def reaction_sum(row, axis):
    return sum(v for c, v in row.items() if c.startswith("reaction_boundary_") and c.endswith(f"_{axis}_N"))


def largest_reaction(rows, axes):
    return max(abs(v) for row in rows for c, v in row.items()
               if c.startswith("reaction_boundary_") and c[-3] in axes)


def check_balance(name, rows, axes, applied=lambda row, axis: 0., with_contact=True):
    """sum_b R_b + C + F = 0 on `axes` at every step, to TOLERANCE of the largest reaction."""
    scale = largest_reaction(rows, axes)
    worst = 0.
    for row in rows:
        for axis in axes:
            contact = row[f"contact_force_{axis}_N"] if with_contact else 0.
            worst = max(worst, abs(reaction_sum(row, axis) + contact + applied(row, axis)))
    check(scale > 0 and worst <= TOLERANCE * scale,
          f"{name}: reactions + contact force + applied loads = 0 on {', '.join(axes)} at all "
          f"{len(rows)} steps: largest imbalance {worst:.2e} N against reactions up to {scale:.4g} N")


patin = sltest.read_prm(os.path.join(root, "prm", "patin_elastic.prm"))
check_balance("patin, generalized Newton", rows_of("patin-newton", patin + sltest.GENERALIZED_NEWTON), "xy")
check_balance("patin, nested loops", rows_of("patin-nested", patin), "y")

elastoplastic = sltest.read_prm(os.path.join(root, "prm", "patin_elastoplastic.prm"))
check_balance("J2 patin, finite strain, generalized Newton",
              rows_of("patin-j2-newton", elastoplastic + sltest.GENERALIZED_NEWTON), "xy")

block_3d = sltest.read_prm(os.path.join(root, "prm", "patin_3d.prm"))
check("set Global refinements = 3" in block_3d, "prm/patin_3d.prm sets 3 global refinements")
block_3d = block_3d.replace("set Global refinements = 3", "set Global refinements = 2")
check_balance("3D block, generalized Newton", rows_of("patin-3d-newton", block_3d + sltest.GENERALIZED_NEWTON),
              "xyz")

# two bodies: the contact forces act on both and cancel; the applied load is p t times 10 mm
patch = sltest.read_prm(os.path.join(root, "prm", "contact_patch_test.prm"))
for entry in ("set Function constants  = p=100", "set Function expression = 0; -p*t"):
    check(entry in patch, f"prm/contact_patch_test.prm sets '{entry}'")
check_balance("two-body patch test, 2 ranks", rows_of("patch", patch, ranks=2), "xy",
              applied=lambda row, axis: -1000. * row["time"] if axis == "y" else 0., with_contact=False)

cook = sltest.read_prm(os.path.join(root, "prm", "cook_membrane.prm"))
for entry in ("set Function constants  = q=6.25", "set Function expression = 0; q*t"):
    check(entry in cook, f"prm/cook_membrane.prm sets '{entry}'")
check_balance("Cook's membrane", rows_of("cook", cook), "xy",
              applied=lambda row, axis: 100. * row["time"] if axis == "y" else 0., with_contact=False)
check.finish()
