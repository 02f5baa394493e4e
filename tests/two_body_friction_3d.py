#!/usr/bin/python3
"""prm/punch_3d_friction.prm as shipped (prm/meshes/punch_3d.geo: a filleted
half-cylinder punch on a block, both deformable, 3D, 1580 hexahedra, Coulomb
friction mu = 0.3, `Complementarity = weighted`): pressed in the first load
step, slid by 0.2 mm in the second (two load steps keep the test short: the
nested loops take about 30 Newton iterations a step here, their geometry loop
reaching its 10 iterations and handing the pairing to the generalized Newton
in each step). The only 3D scene of two deformable bodies with friction.

Run with the nested loops (the default) and with the generalized Newton, each
on 1 and on 2 MPI ranks. Checks: every run exits with 0; the first step
(pressed, not slid) sticks; in each step where every contact node slips
(statistics.csv: points_stick = 0 < points_slip; here the second)
F_t / F_n = mu to 1e-4 relative. Measured: 0.2999975 with both algorithms on
both rank counts (8e-6 relative). Each nodal traction has |t_j| = mu lambda_j
to the Newton tolerance (1e-8 relative residual), so the deviation is not the
solver's; likely it is that F_t is the norm of the vector sum of tractions
lying in tangent planes that differ from node to node on the curved, deforming
surface (as in tests/two_body_slide_3d.py), which only lowers the ratio. 1e-4
leaves a factor 10 above the measured value and is the nested loops' own
friction-loop tolerance.

The 2-rank forces (F_n, F_t, every step) agree with the 1-rank ones of the same
algorithm to 1e-6 relative with the generalized Newton (the same equations
solved to the Newton tolerance; the partition changes only the order of sums
and of the direct solve; measured: identical) and to 1e-4 with the nested
loops (their friction and geometry loops stop at 1e-4 on the change of their
iterates, and rounding that differs with the partition can stop them an
iterate apart; measured 4e-9 here, 1.8e-5 with three load steps). In the
sliding step the two algorithms' forces agree to 2 % (measured 3.4e-3; the
first, stick, step differs by 2.7 % in F_t, 0.1 % in F_n, between the two:
not understood, recorded as found).

Measured wall time (1580 cells, 2 cores, the machine not idle, load ~2):
nested loops 28 s on 1 rank (59 Newton iterations) and 30 s on 2 ranks,
generalized Newton 8 s and 8 s (11 iterations); the whole test 79 s. With
both ranks on one core (taskset -c 0, no MPI binding) the 2-rank runs take
210 s (nested) and 52 s (generalized Newton), the ranks polling for each
other's messages; hence PROCESSORS 2."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
mu = 0.3
prm = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm", "punch_3d_friction.prm")
scene = sltest.read_prm(prm)
forces = {}
for algorithm, extra in (("nested", ""), ("generalized Newton", sltest.GENERALIZED_NEWTON)):
    for ranks in (1, 2):
        name = f"{algorithm}, {ranks} rank(s)"
        out = os.path.join(workdir, f"{algorithm.split()[0]}_{ranks}")
        if not sltest.run_checked(executable, scene + extra, out, check, name, ranks=ranks):
            continue
        statistics = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
        check(len(statistics) == 2, f"{name}: {len(statistics)} load steps (2)")
        check(statistics and statistics[0]["points_slip"] == 0 < statistics[0]["points_stick"],
              f"{name}: the pressed punch sticks in the first step")
        sliding = [row for row in statistics if row["points_stick"] == 0 < row["points_slip"]]
        check(len(sliding) == 1, f"{name}: every contact node slips in {len(sliding)} of the 1 sliding step")
        for row in sliding:
            ratio = row["tangential_force_N"] / row["normal_force_N"]
            check(abs(ratio - mu) <= 1e-4 * mu,
                  f"{name}: t = {row['time']:.3f}, {row['points_slip']:.0f} nodes slip, "
                  f"F_t / F_n = {ratio:.7f} (mu = {mu}, bound 1e-4 relative)")
        forces[(algorithm, ranks)] = [(row["normal_force_N"], row["tangential_force_N"]) for row in statistics]


def difference(a, b):
    """The largest relative difference between two lists of (F_n, F_t) rows."""
    if len(a) != len(b):
        return float("inf")
    return max(abs(x - y) / max(abs(x), abs(y)) for ra, rb in zip(a, b) for x, y in zip(ra, rb))


# the generalized Newton stops at its residual (Newton tolerance 1e-8), the nested loops at
# the friction and geometry loops' 1e-4 on the change of their iterates, where rounding
# that differs with the partition can stop them one iterate apart
for algorithm, bound in (("nested", 1e-4), ("generalized Newton", 1e-6)):
    if (algorithm, 1) in forces and (algorithm, 2) in forces:
        d = difference(forces[(algorithm, 1)], forces[(algorithm, 2)])
        check(d <= bound, f"{algorithm}: F_n, F_t on 2 ranks = on 1 rank to {d:.1e} relative (bound {bound:g})")
if ("nested", 1) in forces and ("generalized Newton", 1) in forces:
    d = difference(forces[("nested", 1)][1:], forces[("generalized Newton", 1)][1:])
    check(d <= 0.02, f"sliding steps: nested and generalized Newton F_n, F_t agree to {d:.1e} relative (bound 0.02)")
check.finish()
