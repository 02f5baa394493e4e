#!/usr/bin/python3
"""Adaptive refinement around the active set, with hanging nodes on the contact
boundary (3D: the half ball of prm/hertz_sphere.prm pressed on a rigid plane).

Three meshes: the contact zone refined uniformly 2 and 3 times (P2, P3), and
the 2-times mesh refined once more around the active set (P_a: the same
contact mesh size where contact is active, hanging nodes on Γc at the edge of
the refined band). Checks: the adapted mesh has multiplier DoFs at hanging
nodes; it resolves the active set like the finer uniform mesh (same number of
contact points in contact); its contact force agrees with the finer uniform
one within the discretisation error, estimated as |P3 - P2|; and it is the
same on 2 MPI ranks (1e-8 relative: only round-off differs).

2D: the coarse Hertz cylinder indented by 0.05 mm, whose contact starts at the single node below
the tip (an active zone of size 0): each cycle refines the cells around it,
so the cells grow and the contact zone is resolved by more points."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "hertz_sphere.prm")) as f:
    base = f.read()


def run(name, local_refinements, cycles, ranks=1):
    text = base.replace("set Local refinements       = 3", f"set Local refinements       = {local_refinements}")
    text += f"\nsubsection Adaptive refinement\n  set Cycles = {cycles}\nend\n"
    out = f"{workdir}/{name}"
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, ranks=ranks)
    last = sltest.read_csv(out + "/output/statistics.csv")[-1]
    return last["normal_force_N"], int(last["points_in_contact"]), log


P2, _, _ = run("uniform-2", 2, 0)
P3, active3, _ = run("uniform-3", 3, 0)
Pa, active_a, log = run("adaptive", 2, 1)
hanging = [line for line in log.splitlines() if "hanging nodes of the contact boundary" in line]
check(len(hanging) == 1, f"the adapted mesh has multiplier DoFs at hanging nodes: {hanging}")
check(active_a == active3, f"active set resolved like the finer uniform mesh: {active_a} = {active3} points")
check(abs(Pa - P3) <= abs(P3 - P2),
      f"contact force {Pa:.1f} N (adaptive) vs {P3:.1f} N (uniform): difference {abs(Pa - P3) / P3:.2%} "
      f"<= discretisation error |P3 - P2| / P3 = {abs(P3 - P2) / P3:.2%}")
Pa2, _, _ = run("adaptive-2-ranks", 2, 1, ranks=2)
check(abs(Pa2 - Pa) <= 1e-8 * Pa, f"2 ranks: {Pa2:.6f} N = 1 rank {Pa:.6f} N")

# the contact at a single vertex (a small indentation: only the node below the
# tip touches on the coarse mesh): the cells around it are refined at every cycle
text = sltest.coarse_hertz() + "".join(sltest.nested_set(path, value) for path, value in (
    ("Boundary conditions/Dirichlet 1/Displacement/Function constants", "delta=0.05"),
    ("Load stepping/Number of load steps", 1),
    ("Adaptive refinement/Cycles", 3),
    ("Adaptive refinement/Criterion", "active set")))
if sltest.run_checked(executable, text, f"{workdir}/point-contact", check, "2D point contact"):
    cycles = sltest.read_csv(f"{workdir}/point-contact/output/refinement_cycles.csv")
    cells = [int(row["cells"]) for row in cycles]
    check(all(b > a for a, b in zip(cells, cells[1:])), f"2D point contact: cells grow every cycle: {cells}")
    first = sltest.read_csv(f"{workdir}/point-contact/output/cycle-0/statistics.csv")[-1]
    last = sltest.read_csv(f"{workdir}/point-contact/output/statistics.csv")[-1]
    check(int(last["points_in_contact"]) > int(first["points_in_contact"]),
          f"2D point contact: points in contact {first['points_in_contact']} -> {last['points_in_contact']}")
check.finish()
