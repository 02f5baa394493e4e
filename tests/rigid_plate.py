#!/usr/bin/python3
"""A rigid plate (`Boundary conditions/Rigid plate <name>`) loads the Hertz cylinder of
prm/hertz_cylinder.prm (R = 100 mm, E = 200000 MPa, nu = 0.3, plane strain) by a resultant
force instead of a prescribed displacement.

1. Frictionless, the plate carrying P = 50000 N/mm downwards (its top face held in x):
   - the contact force equals P to 1e-8 (the plate's equation is the sum of its nodes');
   - a and p0 against Hertz with that P: |a - a_H| <= h/2 + 1 % a_H and the peak within 1 %
     (tests/hertz.py's bounds: the midpoint estimate of the edge, and the finite body
     against the half-space, O((a/R)^2) = 0.3 % here);
   - the same scene with the top face moved by the plate's computed displacement U instead
     (a Dirichlet condition) has the same discrete solution: its force is P to 1e-8.
2. With friction (mu = 0.3, generalized Newton), the plate pressed by P, then pushed sideways
   by Q = 0.5 mu P:
   - F_t = Q and F_n = P to 1e-8 at every step;
   - the cylinder does not roll: the plate moves as one translation, and the loaded zone
     stays centred (|x_left + x_right| <= 2 h);
   - the stick zone shows: the nodes in the middle stick, those near the edges slip, and the
     stick zone shrinks at every step as Q grows. (Cattaneo-Mindlin's c = a sqrt(1 - Q/(mu P))
     is printed, not checked: it holds for elastically similar bodies; against a rigid plane
     the normal and tangential problems couple (Dundurs' beta = 0.29 for nu = 0.3, close to
     mu), the edges already slip inwards under P alone, and the stick zone is smaller);
   - the top face moved by the plate's computed displacements at each step instead (a
     Dirichlet condition through those values) has the same discrete solution: F_t = Q(t),
     F_n = P(t) to 1e-8 and the same stick and slip nodes at every step;
   - the same on 2 MPI ranks: forces and the plate's displacement to 1e-8."""
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
E, NU, R, P, MU = 200000.0, 0.3, 100.0, 50000.0, 0.3
Q = 0.5 * MU * P
E_STAR = E / (1 - NU * NU)
base = sltest.read_prm(os.path.join(root, "prm", "hertz_cylinder.prm"))
start, end = base.index("subsection Boundary conditions"), base.index("subsection Load stepping")


def with_conditions(conditions, mu=0.0, steps=2, end_time=1):
    text = base[:start] + conditions + base[end:]
    text = text.replace("set Friction coefficient = 0", f"set Friction coefficient = {mu}")
    text = text.replace("set Number of load steps = 2", f"set Number of load steps = {steps}\n  set End time = {end_time}")
    text = text.replace("set Local refinements       = 4", "set Local refinements       = 6")
    return text + sltest.QUIET_OUTPUT


HELD_X = """  subsection Dirichlet side
    set Boundary id = 3
    set Components  = x
  end
"""
FRICTIONLESS = with_conditions("""subsection Boundary conditions
""" + HELD_X + f"""  subsection Rigid plate top
    set Boundary id = 3
    set Components  = y
    subsection Force
      set Function expression = 0; -{P}*t
    end
  end
end
""")


def measure(outdir):
    """Last step's statistics and profile; half-width (midpoints), contact spacing, peak."""
    last = sltest.read_csv(os.path.join(outdir, "statistics.csv"))[-1]
    profile = sorted(sltest.last_profile(outdir), key=lambda row: row["x_mm"])
    xs = [row["x_mm"] for row in profile]
    loaded = [i for i, row in enumerate(profile) if row["contact_pressure_MPa"] > 0]
    left, right = loaded[0], loaded[-1]
    a = 0.25 * ((xs[right] + xs[right + 1]) - (xs[left] + xs[left - 1]))
    h = max(xs[right + 1] - xs[right], xs[left] - xs[left - 1])
    return last, profile, a, h, (xs[left], xs[right])


def statuses(outdir, step):
    """The contact status of each node (by x) of a step's profile."""
    profile = sltest.read_csv(os.path.join(outdir, f"profile-{int(step):05d}.csv"))
    return [int(row["status"]) for row in sorted(profile, key=lambda row: row["x_mm"])]


out = os.path.join(workdir, "frictionless")
sltest.run(executable, FRICTIONLESS, out)
last, profile, a, h, _ = measure(os.path.join(out, "output"))
U = last["plate_top_displacement_y_mm"]
check(abs(last["normal_force_N"] - P) <= 1e-8 * P,
      f"frictionless: F_n = {last['normal_force_N']:.10g} N/mm = P, the plate moved U = {U:.6f} mm")
a_h = math.sqrt(4 * P * R / (math.pi * E_STAR))
p0_h = 2 * P / (math.pi * a_h)
p0 = max(row["contact_pressure_MPa"] for row in profile)
check(abs(a - a_h) <= 0.5 * h + 0.01 * a_h,
      f"frictionless: a = {a:.4f} mm, Hertz {a_h:.4f} mm (h = {h:.3f} mm)")
check(abs(p0 - p0_h) <= 0.01 * p0_h, f"frictionless: p0 = {p0:.1f} MPa, Hertz {p0_h:.1f} MPa "
      f"({abs(p0 - p0_h) / p0_h:.2%})")
moved = with_conditions("""subsection Boundary conditions
  subsection Dirichlet top
    set Boundary id = 3
    set Components  = x, y
    subsection Displacement
""" + f"""      set Function expression = 0; {U!r}*t
    end
  end
end
""")
out = os.path.join(workdir, "moved")
sltest.run(executable, moved, out)
force = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]["normal_force_N"]
check(abs(force - P) <= 1e-8 * P,
      f"the top face moved by U instead: F_n = {force:.10g} N/mm = P (difference {force - P:.1e})")

FRICTION = with_conditions(f"""subsection Boundary conditions
  subsection Rigid plate top
    set Boundary id = 3
    set Components  = x, y
    subsection Force
      set Function expression = {Q}*max(t - 1, 0); -{P}*min(t, 1)
    end
  end
end
""", mu=MU, steps=6, end_time=2) + sltest.GENERALIZED_NEWTON
runs = {}
for ranks in (1, 2):
    out = os.path.join(workdir, f"friction-{ranks}")
    sltest.run(executable, FRICTION, out, ranks=ranks)
    rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    runs[ranks] = rows
    worst = max(max(abs(row["tangential_force_N"] - Q * max(row["time"] - 1, 0)),
                    abs(row["normal_force_N"] - P * min(row["time"], 1))) for row in rows)
    check(worst <= 1e-8 * P, f"friction, {ranks} rank(s): F_t = Q(t) and F_n = P(t) at all {len(rows)} "
          f"steps (largest difference {worst:.1e} N/mm)")
    last, profile, a, h, (x_left, x_right) = measure(os.path.join(out, "output"))
    check(abs(x_left + x_right) <= 2 * h,
          f"friction, {ranks} rank(s): the loaded zone stays centred, [{x_left:.3f}, {x_right:.3f}] mm "
          f"(h = {h:.3f}); the plate slid {last['plate_top_displacement_x_mm']:.5f} mm")
    stick = [row["x_mm"] for row in profile if row["status"] == 1]
    slip = [row["x_mm"] for row in profile if row["status"] == 2]
    c = 0.5 * (max(stick) - min(stick)) if stick else 0.
    check(len(stick) >= 3 and len(slip) >= 2 and min(slip) < min(stick) and max(slip) > max(stick),
          f"friction, {ranks} rank(s): {len(stick)} nodes stick in the middle, {len(slip)} slip at the "
          f"edges; stick half-width {c:.3f} mm (Cattaneo-Mindlin, for similar bodies: "
          f"{a * math.sqrt(1 - Q / (MU * P)):.3f} mm)")
    sticking = [statuses(os.path.join(out, "output"), row["step"]).count(1) for row in rows if row["time"] > 1]
    check(all(later < earlier for earlier, later in zip(sticking, sticking[1:])),
          f"friction, {ranks} rank(s): the stick zone shrinks as Q grows: {sticking} nodes")
# the top face moved through the plate's displacements, linear between the step times
rows = runs[1]


def through(column):
    times, values = [0.] + [row["time"] for row in rows], [0.] + [row[column] for row in rows]
    expression = repr(values[-1])
    for k in range(len(times) - 1, 0, -1):
        slope = (values[k] - values[k - 1]) / (times[k] - times[k - 1])
        expression = f"if(t <= {times[k]!r}, {values[k - 1]!r} + {slope!r}*(t - {times[k - 1]!r}), {expression})"
    return expression


moved = with_conditions(f"""subsection Boundary conditions
  subsection Dirichlet top
    set Boundary id = 3
    set Components  = x, y
    subsection Displacement
      set Function expression = {through("plate_top_displacement_x_mm")}; {through("plate_top_displacement_y_mm")}
    end
  end
end
""", mu=MU, steps=6, end_time=2) + sltest.GENERALIZED_NEWTON
out = os.path.join(workdir, "friction-moved")
sltest.run(executable, moved, out)
moved_rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
worst = max(max(abs(m["tangential_force_N"] - r["tangential_force_N"]), abs(m["normal_force_N"] - r["normal_force_N"]))
            for m, r in zip(moved_rows, rows))
same_status = all(statuses(os.path.join(out, "output"), r["step"]) ==
                  statuses(os.path.join(workdir, "friction-1", "output"), r["step"]) for r in rows)
check(len(moved_rows) == len(rows) and worst <= 1e-8 * P and same_status,
      f"the top face moved through the plate's displacements: the forces to {worst:.1e} N/mm at all "
      f"{len(rows)} steps, the same stick and slip nodes: {same_status}")
difference = max(abs(r1[c] - r2[c]) / scale for r1, r2 in zip(runs[1], runs[2])
                 for c, scale in (("tangential_force_N", P), ("normal_force_N", P),
                                  ("plate_top_displacement_x_mm", abs(runs[1][-1]["plate_top_displacement_y_mm"])),
                                  ("plate_top_displacement_y_mm", abs(runs[1][-1]["plate_top_displacement_y_mm"]))))
check(len(runs[1]) == len(runs[2]) and difference <= 1e-8,
      f"2 ranks: the forces and the plate's displacement of 1 rank (largest relative difference {difference:.1e})")
check.finish()
