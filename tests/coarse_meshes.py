#!/usr/bin/python3
"""A coarser mesh gives a less accurate answer, not none (issue 49): a half cylinder
(R = 10 mm) on a deformable block, two bodies with non-matching quadrilaterals, Coulomb
mu = 0.3, the default contact settings (Complementarity = automatic, weighted for two bodies;
Gauss-Lobatto; r_n = 1e4, r_t = 1),
pressed 0.1 mm by its top and then slid 1 mm, 10 load steps, on four meshes whose cells
halve from one to the next (3 to 24 segments on a quarter of the arc), with the nested loops
and the generalized Newton.

Every run must end (exit 0) with the cylinder's equilibrium (the contact force and the
reaction of its top opposite, to the geometry loop's tolerance 1e-4 of the load with the
nested loops, 1e-6 with the generalized Newton) and the friction law held at every step.
The answers must converge with the mesh: the normal force at the end of the pressing on the
three finer meshes within 5 % of the finest (556, 532, 534 N/mm with the default weighted
conditions), and each one
closer to the finest than the coarser one before it; the coarsest (3 segments on a
quarter of the arc, a 60-degree faceting of the cylinder) is only required to run."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()

# nodes on a quarter arc, along the block's top, along its sides; the largest cell size
MESHES = ((4, 5, 2, 12), (7, 9, 3, 6), (13, 18, 6, 3), (25, 35, 11, 1.5))

PRM = sltest.cylinder_on_block_prm("cylinder_on_block.geo", """  subsection Dirichlet press
    set Boundary id = cyl_top
    set Components  = x, y
    subsection Displacement
      set Function expression = if(t < 0.5, 0, 2*(t-0.5)); -0.1*min(2*t,1)
    end
  end
""", 10)

# The contact force is integrated with the pairing of the converged state; the nested loops
# solve with that of the last geometry iteration, which differs by the geometry loop's
# tolerance (relative displacement change 1e-4); the generalized Newton linearises it.
for algorithm, extra, balance in (("nested loops", "", 1e-4),
                                  ("generalized Newton", sltest.GENERALIZED_NEWTON, 1e-6)):
    pressed = []
    for arc, top, side, h in MESHES:
        name = f"{arc - 1} segments, {algorithm}"
        directory = os.path.join(workdir, algorithm.replace(" ", "_"), str(arc))
        os.makedirs(directory, exist_ok=True)
        with open(os.path.join(directory, "cylinder_on_block.geo"), "w") as f:
            f.write(sltest.cylinder_on_block_geo(arc, top, side, h))
        if not sltest.run_checked(executable, PRM + extra, directory, check, name):
            pressed.append(None)
            continue
        steps = sltest.read_csv(os.path.join(directory, "output", "statistics.csv"))
        check(len(steps) == 10, f"{name}: 10 load steps written ({len(steps)})")
        # Gmsh numbers the physical curves in the order of the .geo: cyl_top is 2
        load = max(abs(r["reaction_boundary_2_y_N"]) for r in steps)
        imbalance = max(abs(r[f"contact_force_{d}_N"] + r[f"reaction_boundary_2_{d}_N"])
                        for r in steps for d in "xy")
        check(imbalance <= balance * load,
              f"{name}: the contact force balances the reaction of the cylinder's top "
              f"(largest difference {imbalance:.3g} N/mm of {load:.4g})")
        violations = sum(r["friction_law_violations"] for r in steps)
        check(violations == 0, f"{name}: the friction law holds at every step ({violations:.0f} "
                               "violations)")
        end_of_pressing = [r for r in steps if abs(r["time"] - 0.5) < 1e-9]
        pressed.append(end_of_pressing[0]["normal_force_N"] if end_of_pressing else None)
    print(f"{algorithm}: F_n at the end of the pressing, coarsest to finest: {pressed}")
    if None in pressed[1:]:
        check(False, f"{algorithm}: every mesh but the coarsest ran")
        continue
    finest = pressed[-1]
    errors = [abs(f - finest) for f in pressed[1:-1]]
    check(all(e <= 0.05 * finest for e in errors),
          f"{algorithm}: F_n on the finer meshes within 5 % of the finest's {finest:.4g} N/mm "
          f"(differences {', '.join(f'{e:.3g}' for e in errors)})")
    check(all(a >= b for a, b in zip(errors, errors[1:])),
          f"{algorithm}: each finer mesh closer to the finest")
check.finish()
