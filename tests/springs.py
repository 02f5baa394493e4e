#!/usr/bin/python3
"""Springs (`Boundary conditions/Spring <name>`: the traction -K (u - u_0)) on prm/spring_pad.prm:
a pad pressed onto a rigid plane by p = 10 MPa on its top (L = 100 mm) and pulled along it by
springs of stiffness K = 1 MPa/mm on its left face (H = 50 mm), whose ends move by u_0(t),
friction mu = 0.3.

- Equilibrium (generalized Newton): the springs' force (statistics.csv, reaction of the
  springs' boundary) balances the contact force at every step, to 1e-8 of it (the residual is
  at the solver's tolerance). The nested loops evaluate the tangential force with the friction
  threshold of their last friction check, so it balances to the friction loop's tolerance only
  (tests/reactions.py); they are checked on the rest.
- Stick: while the springs' force is below mu F_n, F_t equals it.
- Full slip: F_t = mu F_n = mu p L to 1e-8, and the pad's slip is the spring law's: the springs
  carry K H (u_0 - u_mean) = mu p L, so every contact node has slid u_0 - mu p L / (K H). The
  nodes differ from the mean displacement of the left face by the pad's own deformation, bounded
  by the shear strain mu p / G over the height plus the springs' compression K s / E over the
  length (s the stretch): 5e-3 mm here, against a slip of 4 mm; the bound is doubled.
- The same on 2 MPI ranks; the condition names are free: the same run with the subsections
  named `Neumann 7` and `Spring 12` gives the same statistics."""
import glob
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
text = sltest.read_prm(os.path.join(root, "prm", "spring_pad.prm"))
P, L, H, K, MU, D, E, NU = 10., 100., 50., 1., 0.3, 10., 200000., 0.3
F_N = P * L
G = E / (2 * (1 + NU))


def u_0(t):
    return D * max(t - 0.2, 0.) / 0.8


def slid(outdir):
    """Each contact node's slip summed over the steps (x_mm -> mm)."""
    total = {}
    for profile in sorted(glob.glob(os.path.join(outdir, "profile-*.csv"))):
        for row in sltest.read_csv(profile):
            total[row["x_mm"]] = total.get(row["x_mm"], 0.) + row["slip_increment_x_mm"]
    return total


runs = {}
renamed = text.replace("subsection Neumann pressure", "subsection Neumann 7").replace(
    "subsection Spring pull", "subsection Spring 12")
check(renamed.count("Neumann 7") == 1 and renamed.count("Spring 12") == 1, "the scene has the subsections to rename")
newton = text + sltest.GENERALIZED_NEWTON
for name, ranks, prm in (("1 rank", 1, newton), ("2 ranks", 2, newton),
                         ("renamed", 1, renamed + sltest.GENERALIZED_NEWTON), ("nested", 1, text)):
    out = os.path.join(workdir, name.replace(" ", "_"))
    sltest.run(executable, prm + "\nsubsection Output\n  set Output directory = output\n"
               "  set Write vtu = false\nend\n", out, ranks=ranks)
    rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    runs[name] = rows
    spring = [row["reaction_boundary_0_x_N"] for row in rows]
    worst = max(abs(s + row["contact_force_x_N"]) for s, row in zip(spring, rows))
    if name != "nested":
        check(worst <= 1e-8 * max(abs(s) for s in spring),
              f"{name}: the springs' force balances the contact force at all {len(rows)} steps "
              f"(largest imbalance {worst:.2e} N against up to {max(spring):.1f} N)")
    check(all(abs(row["normal_force_N"] - P * L * min(row["time"] / 0.2, 1.)) <= 1e-8 * F_N for row in rows),
          f"{name}: F_n = p L at every step")
    stick = [row for row, s in zip(rows, spring) if s < MU * F_N * (1 - 1e-3)]
    slip = [row for row in rows if row["points_stick"] == 0 and row["time"] > 0.2]
    check(len(stick) >= 3 and len(slip) >= 3, f"{name}: {len(stick)} steps below mu F_n, {len(slip)} in full slip")
    check(all(abs(row["tangential_force_N"] - MU * F_N) <= 1e-8 * F_N for row in slip),
          f"{name}: F_t = mu F_n = {MU * F_N:g} N in full slip: "
          + ", ".join(f"{row['tangential_force_N']:.10g}" for row in slip))
    if ranks == 1 and name in ("1 rank", "nested"):
        total = slid(os.path.join(out, "output"))
        t = rows[-1]["time"]
        expected = u_0(t) - MU * F_N / (K * H)
        bound = 2 * (MU * P / G * H + K * (MU * F_N / (K * H)) / E * L)
        deviation = max(abs(v - expected) for v in total.values())
        check(len(total) > 10 and deviation <= bound,
              f"{name}: the {len(total)} contact nodes slid {min(total.values()):.6f}-"
              f"{max(total.values()):.6f} mm, the spring law's {expected:.6f} mm (off by "
              f"{deviation:.2e} <= {bound:.1e} mm, the pad's deformation)")
for name in ("2 ranks", "renamed"):
    difference = max(abs(a[c] - b[c]) for a, b in zip(runs[name], runs["1 rank"])
                     for c in ("tangential_force_N", "reaction_boundary_0_x_N", "normal_force_N"))
    check(len(runs[name]) == len(runs["1 rank"]) and difference <= 1e-8 * F_N,
          f"{name}: the forces of the 1-rank run at every step (largest difference {difference:.1e} N)")
check.finish()
