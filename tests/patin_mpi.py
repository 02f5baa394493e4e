#!/usr/bin/python3
"""The elastic patin (prm/patin_elastic.prm, the built-in default scene) runs to
the end, on one MPI rank and on two, and both give the same statistics: the
same loop counts and contact point counts in every step, and the same forces
to solver tolerance. The same for the neo-Hookean patin with the generalized
Newton (all three loops folded). Also runs the 3D block once."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    base = f.read().replace("output-patin-elastic", "output")

runs = {}
for ranks in (1, 2):
    out = f"{workdir}/np{ranks}"
    code, log = sltest.run(executable, base, out, ranks=ranks)
    runs[ranks] = sltest.read_csv(out + "/output/statistics.csv")
    check(len(runs[ranks]) == 10 and abs(runs[ranks][-1]["time"] - 1.0) < 1e-12,
          f"{ranks} rank(s): 10 load steps up to t = 1")

counts = ["geometry_iterations", "friction_iterations", "status_iterations", "newton_iterations",
          "points_in_contact", "points_stick", "points_slip"]
forces = ["normal_force_N", "tangential_force_N", "contact_force_x_N", "contact_force_y_N"]
for one, two in zip(runs[1], runs[2]):
    step = int(one["step"])
    check(all(one[c] == two[c] for c in counts), f"step {step}: same loop and point counts on 1 and 2 ranks")
    scale = abs(one["normal_force_N"])
    worst = max(abs(one[f] - two[f]) for f in forces) / scale
    check(worst < 1e-9, f"step {step}: same forces on 1 and 2 ranks (max difference {worst:.1e} of F_n)")

# the same solution: the contact surface, vertex by vertex, at every step
fields = ["contact_pressure_MPa", "tangential_traction_x_MPa", "gap_mm", "slip_increment_x_mm"]
worst = 0.0
for step in range(1, 11):
    p1 = sltest.read_csv(f"{workdir}/np1/output/profile-{step:05d}.csv")
    p2 = sltest.read_csv(f"{workdir}/np2/output/profile-{step:05d}.csv")
    check(len(p1) == len(p2) and all(a["x_mm"] == b["x_mm"] for a, b in zip(p1, p2)),
          f"step {step}: the same {len(p1)} contact vertices on 1 and 2 ranks")
    # tractions relative to the peak pressure, lengths relative to u0 = 0.5 mm
    pressure = max(r["contact_pressure_MPa"] for r in p1)
    for f in fields:
        scale = pressure if f.endswith("MPa") else 0.5
        worst = max(worst, max(abs(a[f] - b[f]) for a, b in zip(p1, p2)) / scale)
check(worst < 1e-9, f"the same contact fields on 1 and 2 ranks (max difference {worst:.1e} "
      "of the peak pressure, or of u0 for gap and slip)")

summary = sltest.read_csv(f"{workdir}/np2/output/run_summary.csv")[0]
check(summary["mpi_ranks"] == 2 and summary["load_steps"] == 10
      and summary["newton_iterations"] == sum(r["newton_iterations"] for r in runs[2]),
      "run_summary.csv: 2 ranks, 10 steps, Newton total = sum over statistics.csv")

last = runs[1][-1]
check(last["points_slip"] == last["points_in_contact"] > 0,
      "the patin slides at the end: every contact point slips")
check(abs(last["tangential_force_N"] - 0.1 * last["normal_force_N"]) < 1e-8 * last["normal_force_N"],
      "sliding: F_t = mu F_n")

# the generalized Newton on the neo-Hookean patin (coarser mesh), 1 and 2 ranks
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_neo_hookean.prm")) as f:
    neo = f.read() + sltest.GENERALIZED_NEWTON
neo += "\nsubsection Geometry\n  subsection block\n    set Global refinements = 3\n  end\nend\n"
newton_runs = {}
for ranks in (1, 2):
    out = f"{workdir}/newton-np{ranks}"
    sltest.run(executable, neo + sltest.QUIET_OUTPUT, out, ranks=ranks)
    newton_runs[ranks] = sltest.read_csv(out + "/output/statistics.csv")
same_counts = len(newton_runs[1]) == len(newton_runs[2]) and all(
    one[c] == two[c] for one, two in zip(newton_runs[1], newton_runs[2]) for c in counts)
check(same_counts, f"generalized Newton: the same loop and point counts on 1 and 2 ranks in "
      f"{len(newton_runs[1])} steps")
worst = max(abs(one[f] - two[f]) / abs(one["normal_force_N"])
            for one, two in zip(newton_runs[1], newton_runs[2]) for f in forces)
check(worst < 1e-9, f"generalized Newton: the same forces on 1 and 2 ranks (max difference {worst:.1e} of F_n)")

# 3D: a block on a rigid plane, pressed then slid
text3d = base.replace("set Dimension = 2", "set Dimension = 3")
text3d = text3d.replace("set Subdivisions       = 2, 1", "set Subdivisions       = 2, 1, 1")
text3d = text3d.replace("set Global refinements = 4", "set Global refinements = 2")
text3d = text3d.replace("set Normal = 0, 1", "set Normal = 0, 0, 1").replace("set Point  = 0, 0", "set Point  = 0, 0, 0")
text3d = text3d.replace("-u0*min(t/0.5, 1)", "0; -u0*min(t/0.5, 1)").replace("x,y,t", "x,y,z,t")
text3d = text3d.replace("set Components  = x, y", "set Components  = x, y, z")
out = f"{workdir}/3d"
sltest.run(executable, text3d, out, ranks=2)
s3 = sltest.read_csv(out + "/output/statistics.csv")
check(len(s3) == 10 and s3[-1]["points_slip"] == s3[-1]["points_in_contact"] > 0,
      "3D block on 2 ranks: 10 steps, slides at the end")
# In 3D the lateral Poisson expansion spreads the slip directions, so the
# resultant |F_t| lies just below mu F_n (never above it, up to the friction-loop
# tolerance 1e-4 on the thresholds).
ft, fn = s3[-1]["tangential_force_N"], s3[-1]["normal_force_N"]
check(0.99 * 0.1 * fn < ft <= 0.1 * fn * (1 + 1e-4),
      f"3D sliding: 0.99 mu F_n < |F_t| = {ft:.3f} <= mu F_n = {0.1 * fn:.3f}")
check.finish()
