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
same on 2 MPI ranks (1e-8 relative: only round-off differs)."""
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
check.finish()
