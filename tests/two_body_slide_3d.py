#!/usr/bin/python3
"""Two 3D blocks of hexahedra (tests/scenes/two_blocks_3d.geo, refined once: 8 x 8
faces on the slave against 6 x 6 on the master) pressed by 0.1 mm and slid by
1 mm with Coulomb friction (mu = 0.2), with `Complementarity = weighted`, the
nested loops and the generalized Newton.

Before the tangent basis was made to keep its axis on a nearly flat deformable
master (it jumped between e_x and e_y where |n_x| = |n_y|, turning the basis of
Lambda by 90 degrees between iterates) this scene stopped at the onset of
sliding after 5 step cuts with both algorithms; the generalized Newton also
needs the linearised pairing of the deformable master.

Checks: both algorithms converge over the 10 load steps without a step cut;
in the last step every node slips and |t_j| = mu lambda_j at every node (to
1e-8 with the threshold linearised, to the friction loop's 1e-4 with it
iterated), and F_t / F_n = mu to 1e-4 (the tangential force is the norm of
the vector sum of the tractions on a surface that tilts as the blocks deform);
the generalized Newton takes fewer Newton iterations than the nested loops."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
mu = 0.2
scene = (sltest.two_blocks(3, "two_blocks_3d.geo", mu, refinements=1) +
         sltest.nested_set("Contact/Complementarity", "weighted") +
         sltest.blocks_pressed_and_slid(0.1, 0.2, 10))
iterations = {}
for algorithm, extra in (("nested", ""), ("generalized Newton", sltest.GENERALIZED_NEWTON)):
    out = os.path.join(workdir, algorithm.split()[0])
    # (Newton to 1e-10: the per-node law is checked to 1e-8)
    newton = sltest.nested_set("Nonlinear solver/Newton/Tolerance", 1e-10)
    if not sltest.run_checked(executable, scene + extra + newton, out, check, algorithm):
        continue
    statistics = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    cuts = sum(row["step_cuts"] for row in statistics)
    check(len(statistics) == 10 and cuts == 0, f"{algorithm}: {len(statistics)} load steps, {cuts:.0f} step cuts")
    iterations[algorithm] = statistics[-1]["cumulative_newton_iterations"]
    last, nodes = statistics[-1], sltest.last_profile(os.path.join(out, "output"))
    check(last["points_stick"] == 0 and last["points_slip"] == last["points_in_contact"] > 0,
          f"{algorithm}: every node in contact slips in the last step ({last['points_slip']:.0f} of "
          f"{last['points_in_contact']:.0f})")
    peak = max(row["contact_pressure_MPa"] for row in nodes)
    law = max(abs(sum(row[f"tangential_traction_{c}_MPa"] ** 2 for c in "xyz") ** 0.5 - mu * row["contact_pressure_MPa"])
              for row in nodes) / (mu * peak)
    bound = 1e-8 if extra else 1e-4
    check(law <= bound, f"{algorithm}: |t_j| = mu lambda_j at every node to {law:.1e} of mu p_max (bound {bound:g})")
    ratio = last["tangential_force_N"] / last["normal_force_N"]
    check(abs(ratio - mu) <= 1e-4 * mu, f"{algorithm}: F_t / F_n = {ratio:.7f} (mu = {mu})")
if len(iterations) == 2:
    check(iterations["generalized Newton"] < iterations["nested"],
          f"Newton iterations: generalized Newton {iterations['generalized Newton']:.0f}, "
          f"nested {iterations['nested']:.0f}")
check.finish()
