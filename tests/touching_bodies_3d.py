#!/usr/bin/python3
"""Two deformable 3D bodies that touch at the start (gap exactly zero along a
line), with the default contact quadrature (Gauss-Lobatto): the filleted
half-cylinder punch of prm/punch_3d_friction.prm (prm/meshes/punch_3d.geo,
1580 hexahedra) resting on its block, its lowest line at z = 0 on the block's
top. The shipped scene uses the Gauss quadrature; here the `Contact
quadrature` entry is removed from it (one load step, the loads below), so
the contact points sit at the multiplier nodes, some exactly on the block's top.

Four cases, each one load step with the generalized Newton
(Nonlinear solver/*/Method = newton; the nested loops reach the same states
but take 3-6 times as long here, their geometry loop handing the pairing to
the generalized Newton after 10 iterations):
 - pointwise and weighted complementarity, frictionless, the punch pressed by a
   force F = 2000 N on a rigid plate tied to its top in z (held in x, y by a
   Dirichlet condition there, as a frictionless contact holds nothing
   sideways). With the weighted conditions no node touches at the start (a
   node's weighted gap ∫ψ_j g_n / ∫ψ_j is positive on the curved surface), the
   first system is singular, and the nearest nodes start in contact (the log
   says so); with the pointwise ones the touching points start in contact.
 - pointwise and weighted complementarity, Coulomb mu = 0.3, the punch's top
   pressed down by a prescribed 0.02 mm.

Checks: exit 0 without a step cut; the statistics a run reports are there
(loop counts, points in contact); points are in contact; the contact force
balances the loads: with the force, its z component and the reaction of the
block's fixed bottom are F (to 1e-6: the Newton tolerance is 1e-8 of the
force scale, so a balance off by 1e-6 is not round-off); with the prescribed
displacement, its z component equals the reaction of the block's bottom (the
block's equilibrium, to 1e-6) and is positive (compression). The normal force
F_n is the sum over the contact points of the pressure along the deformed
master's normal, which tilts as the block deforms: it is F_z up to that tilt
(measured 2000.009 and 2000.025 N against F_z = 2000 N); it is checked to 1e-3.

Measured on main at 33dbf51: all four exit 0 (5-7 Newton iterations each;
F_z = 2000.000000 N in the force cases, 4228.96 N pointwise and 3682.57 N
weighted under the displacement); the whole test 196 s wall but 22 s of CPU
(2 cores shared with other builds, load ~10). The weighted force case starts
with one failed (singular) attempt, counted in
failed_attempt_newton_iterations, not as a step cut."""
import os
import re
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
# the shipped scene with its `Contact quadrature = Gauss` removed (the default, Gauss-Lobatto,
# remains), one load step, and its conditions and loads overridden below (a later `set` wins)
shipped = sltest.read_prm(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                                       "punch_3d_friction.prm"))
base = re.sub(r"\n\s*set Contact quadrature\s*=.*", "", shipped)
LOAD = 2000.  # N, on the punch's top
# the Gmsh physical surfaces of punch_3d.geo in their order: punch_top 1, punch_contact 2,
# block_top 3, block_bottom 4 (the reaction columns are named by id)
BLOCK_BOTTOM_Z = "reaction_boundary_4_z_N"
# the punch's top held in x, y and pressed in z by a force on a rigid plate
FORCE = sltest.nested_set("Boundary conditions/Dirichlet 2/Components", "x, y") + f"""
subsection Boundary conditions
  subsection Rigid plate 1
    set Boundary id = punch_top
    set Components  = z
    subsection Force
      set Function expression = 0; 0; -{LOAD}*t
      set Variable names      = x,y,z,t
    end
  end
end
"""
# the punch's top pressed down by 0.02 mm, not slid (in FORCE only its x, y = 0 are used)
PRESSED = sltest.nested_set("Boundary conditions/Dirichlet 2/Displacement/Function expression",
                            "0; 0; -0.02*t")


def scene(complementarity, mu, loading):
    return (base + sltest.nested_set("Contact/Complementarity", complementarity) +
            sltest.nested_set("Contact/Friction law/Coulomb/Friction coefficient", mu) +
            sltest.nested_set("Load stepping/Number of load steps", 1) + PRESSED + loading +
            sltest.GENERALIZED_NEWTON)


check("Contact quadrature" not in scene("pointwise", 0, FORCE), "the contact quadrature is the default")
for complementarity in ("pointwise", "weighted"):
    for mu, loading, name in ((0, FORCE, "frictionless, force"), (0.3, "", "mu = 0.3, displacement")):
        case = f"{complementarity}, {name}"
        out = os.path.join(workdir, f"{complementarity}_{mu}")
        if not sltest.run_checked(executable, scene(complementarity, mu, loading), out, check, case):
            continue
        rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
        check(len(rows) == 1 and rows[0]["step_cuts"] == 0, f"{case}: one load step, no step cut")
        if len(rows) != 1:
            continue
        row = rows[0]
        check(all(row[c] >= 1 for c in ("geometry_iterations", "friction_iterations", "status_iterations",
                                        "newton_iterations")),
              f"{case}: loop counts reported ({row['geometry_iterations']:.0f} x "
              f"{row['friction_iterations']:.0f} x {row['status_iterations']:.0f}, "
              f"{row['newton_iterations']:.0f} Newton)")
        check(0 < row["points_in_contact"] <= row["contact_points"],
              f"{case}: {row['points_in_contact']:.0f} of {row['contact_points']:.0f} points in contact")
        fz, support = row["contact_force_z_N"], row[BLOCK_BOTTOM_Z]
        check(abs(fz - support) <= 1e-6 * abs(support) and fz > 0,
              f"{case}: contact force F_z = {fz:.6f} N balances the block's support {support:.6f} N")
        if loading is FORCE:
            check(abs(support - LOAD) <= 1e-6 * LOAD, f"{case}: the block carries the load, {support:.6f} N")
        check(abs(row["normal_force_N"] - fz) <= 1e-3 * fz,
              f"{case}: F_n = {row['normal_force_N']:.4f} N = F_z to 1e-3")
check.finish()
