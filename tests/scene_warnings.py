#!/usr/bin/python3
"""Scenes that run but not as the user meant are named in a warning.

- Volumetric locking: the patin (Q1/P1, and Q2/P1) with nu = 0.4999 (K = 3333 G)
  is far too stiff; the run must warn, naming the material's subsection, the pair
  and the F-bar formulation; with nu = 0.3, with Q2 displacements at nu = 0.49, or
  with `Volumetric formulation = F-bar` (Q1) or `mixed` (Q2), it must not.
- A prescribed displacement not zero at t = 0 (`0; -0.015`, constant in t) is
  applied whole in the first step, and cutting that step cannot reduce it: the
  run must warn, naming the entry; and r_t = automatic must take the length of
  that first increment (0.015 mm), not the mesh size.
- `Obstacle/Motion` the scene cannot follow: in a two-body scene (the two
  cylinders) there is no obstacle to move, and in an axisymmetric model (the
  axisymmetric Hertz ball) a radial motion is no motion of a body of revolution:
  both must warn, naming the entry; without a motion, neither warns.
- An obstacle that reaches into the body outside its contact surface (the
  coarse Hertz cylinder, `Contact zone radius = 10`): with the plane 3 mm above
  the pole before the first step, and with the plane moved up 5 mm by
  `Obstacle/Motion` at the end time (the body undeformed), the run must warn
  before the first step, naming `Contact/Contact boundary ids`, the boundary
  reached (0), how deep, and the zone radius's entry; with the shipped zone
  radius (20) and a 1 mm motion it must not.
- An axisymmetric model (the axisymmetric Hertz ball) with an obstacle that is
  no body of revolution about the axis: a tilted plane must warn, naming
  `Obstacle/plane/Normal`, a ball off the axis `Obstacle/ball/Center`; a ball
  on the axis must not warn.
- The size of a run, estimated before the mesh is refined (Geometry::SizeCheck): every run
  prints it (`size estimate ...`, the cell count that of the refined block); the 3D patin with
  `Global refinements = 12` is refused at once (exit non-zero, in seconds, naming
  `Geometry/block/Global refinements` and the machine's memory); 10^7 load steps warn,
  naming `Load stepping/Number of load steps`, before the first load step's line."""
import os
import re
import sys
import time
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    patin = f.read()
fast = sltest.nested_set("Geometry/block/Global refinements", 2) + \
    sltest.nested_set("Load stepping/Number of load steps", 2)


def run(name, text):
    code, log = sltest.run(executable, text + fast + sltest.QUIET_OUTPUT, f"{workdir}/{name}",
                           expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    return log


for name, nu, pair, warned, extra in (
        ("Q1 nu=0.4999", 0.4999, "Q1/P1", True, ""),
        ("Q1 nu=0.3", 0.3, "Q1/P1", False, ""),
        ("Q2 nu=0.49", 0.49, "Q2/P1", False, ""),
        ("Q1 nu=0.4999 F-bar", 0.4999, "Q1/P1", False, sltest.nested_set("Material/Volumetric formulation", "F-bar")),
        ("Q2 nu=0.4999", 0.4999, "Q2/P1", True, ""),
        ("Q2 nu=0.4999 mixed", 0.4999, "Q2/P1", False, sltest.nested_set("Material/Volumetric formulation", "mixed"))):
    log = run(name.replace(" ", "_"), patin.replace("set Poisson's ratio = 0.3", f"set Poisson's ratio = {nu}")
              .replace("set Finite element pair  = Q1/P1", f"set Finite element pair  = {pair}") + extra)
    said = "locks volumetrically" in log
    check(said == warned and (not warned or ("WARNING: Material:" in log and pair in log
                                             and "Volumetric formulation = F-bar" in log)),
          f"{name}: locking warning {'given, naming Material, ' + pair + ' and F-bar' if warned else 'absent'}"
          f" ({said})")

log = run("constant_dirichlet",
          patin.replace("if(t < 0.5, 0, u0*(t - 0.5)/0.5); -u0*min(t/0.5, 1)", "0; -0.015"))
check("WARNING: Boundary conditions/Dirichlet 1/Displacement: the prescribed displacement is not "
      "zero at t = 0" in log, "constant Dirichlet: warning naming the entry")
match = re.search(r"r_t = automatic: .* \(l = ([0-9.e+-]+) mm", log)
check(match is not None and abs(float(match.group(1)) - 0.015) < 1e-12,
      f"constant Dirichlet: r_t's length is the first increment 0.015 mm ({match.group(1) if match else None})")
log = run("ramped_dirichlet", patin)
check("not zero at t = 0" not in log, "ramped Dirichlet: no warning")

prm_directory = os.path.join(os.path.dirname(__file__), "..", "prm")
one_step = sltest.nested_set("Load stepping/Number of load steps", 1)
radial = sltest.nested_set("Obstacle/Motion/Function expression", "0.01*t; 0")
for name, scene, motion, warning in (
        ("two_bodies_moved_obstacle", "two_cylinders.prm", radial,
         "WARNING: Obstacle/Motion moves the rigid obstacle, but this scene has two deformable bodies"),
        ("two_bodies", "two_cylinders.prm", "", None),
        ("axisymmetric_radial_motion", "hertz_axisymmetric.prm", radial,
         "WARNING: Obstacle/Motion moves the obstacle radially in an axisymmetric model"),
        ("axisymmetric", "hertz_axisymmetric.prm", "", None)):
    code, log = sltest.run(executable,
                           sltest.read_prm(os.path.join(prm_directory, scene)) + one_step + motion +
                           sltest.QUIET_OUTPUT, f"{workdir}/{name}", expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    check((warning in log) if warning else ("Obstacle/Motion" not in log),
          f"{name}: " + ("warns, naming Obstacle/Motion" if warning else "no motion warning"))

# an obstacle reaching into the body outside Γc, before the first step or at the end time
hertz = sltest.coarse_hertz() + one_step + sltest.QUIET_OUTPUT
for name, settings, warnings in (
        ("pass_through_at_start", [("Obstacle/plane/Point", "0, 3"),
                                   ("Geometry/half ball/Contact zone radius", "10")],
         ["before the first step"]),
        ("pass_through_at_end", [("Obstacle/Motion/Function expression", "0; 5*t"),
                                 ("Geometry/half ball/Contact zone radius", "10")],
         ["at the end time, with the obstacle where Obstacle/Motion takes it"]),
        ("no_pass_through", [("Obstacle/Motion/Function expression", "0; t")], [])):
    text = hertz.replace("delta=1.5", "delta=0") + "".join(sltest.nested_set(*setting) for setting in settings)
    code, log = sltest.run(executable, text, f"{workdir}/{name}", expect_success=False, timeout=600)
    start = log.find("WARNING: the obstacle reaches into the body outside its contact surface "
                     "(Contact/Contact boundary ids = 2)")
    said = log[start:log.find("\n", log.find("Add those boundaries", start))] if start >= 0 else ""
    first_step = re.search(r"^step +1 ", log, re.MULTILINE)
    if warnings:
        check(start >= 0 and (first_step is None or start < first_step.start()) and
              re.search(r"\n  boundary 0: [0-9.]+ mm deep at \(", said) is not None and
              all(w in said for w in warnings) and
              "or raise Geometry/half ball/Contact zone radius" in said and
              ("before the first step" in said) == ("before the first step" in warnings),
              f"{name}: warned before the first step, naming Contact/Contact boundary ids, "
              f"boundary 0, its depth and the zone radius ({said[:300]!r})")
    else:
        check(start < 0 and "reaches into the body" not in log, f"{name}: no pass-through warning")

# an axisymmetric model's obstacle that is no body of revolution about the axis
axisymmetric = sltest.read_prm(os.path.join(prm_directory, "hertz_axisymmetric.prm")) + one_step + \
    sltest.nested_set("Geometry/half ball/Global refinements", 2) + \
    sltest.nested_set("Geometry/half ball/Local refinements", 2) + sltest.QUIET_OUTPUT
ball = [("Obstacle/Model", "ball"), ("Obstacle/ball/Radius", "100")]
for name, settings, entry in (
        ("axisymmetric_tilted_plane", [("Obstacle/plane/Normal", "0.1, 1")], "Obstacle/plane/Normal points along"),
        ("axisymmetric_ball_off_axis", ball + [("Obstacle/ball/Center", "30, -100")],
         "Obstacle/ball/Center = 30 -100 lies 30 mm off the axis"),
        ("axisymmetric_ball_on_axis", ball + [("Obstacle/ball/Center", "0, -100")], None)):
    code, log = sltest.run(executable, axisymmetric + "".join(sltest.nested_set(*setting) for setting in settings),
                           f"{workdir}/{name}", expect_success=False)
    warned = "WARNING: the obstacle is no body of revolution about the axis x = 0 of the " \
             "axisymmetric model (Geometry/Axisymmetric = true)" in log
    check(code == 0 and (warned and entry in log if entry else not warned),
          f"{name}: exit code {code}, " + (f"warns, naming {entry.split(' ')[0]}" if entry else "no warning")
          + f" ({warned})")

# --- the size of the run, before the mesh is refined --------------------------------------
log = run("size_estimate", patin)
estimate = re.search(r"size estimate .*: about ([0-9.e+]+) cells, ([0-9.e+]+) displacement DoFs", log)
cells = re.search(r"stabilized_lagrangian: 2D, ([0-9]+) cells", log)
check(estimate is not None and cells is not None and log.index("size estimate") < log.index("stabilized_lagrangian: 2D")
      and abs(float(estimate.group(1)) - int(cells.group(1))) <= 0.05 * int(cells.group(1)),
      f"a normal run prints the size estimate before its banner, the block's cells to 2 digits "
      f"({estimate.group(0) if estimate else None}; {cells.group(1) if cells else None} cells)")

patin_3d = sltest.read_prm(os.path.join(prm_directory, "patin_3d.prm"))
check("set Global refinements = 3" in patin_3d, "prm/patin_3d.prm sets 'Global refinements = 3'")
start = time.time()
code, log = sltest.run(executable, patin_3d.replace("set Global refinements = 3", "set Global refinements = 12") +
                       sltest.QUIET_OUTPUT, f"{workdir}/refinements_12", expect_success=False, timeout=120)
seconds = time.time() - start
check(code != 0 and "Geometry/block/Global refinements = 12" in log and "of memory of this machine" in log
      and "step   1" not in log and seconds < 20,
      f"3D patin with 12 refinements: refused in {seconds:.1f} s (exit {code}), naming the entry and the "
      f"machine's memory: {log.strip().splitlines()[-1] if log.strip() else ''}")

code, log = sltest.run(executable, patin + fast + sltest.nested_set("Load stepping/Number of load steps", 10**7) +
                       sltest.nested_set("Load stepping/Wall time limit", 3) + sltest.QUIET_OUTPUT,
                       f"{workdir}/ten_million_steps", expect_success=False, timeout=300)
warned = re.search(r"^WARNING: .*Load stepping/Number of load steps = 10000000", log, re.MULTILINE)
warning = warned.start() if warned else -1
first_step = re.search(r"^step +1 ", log, re.MULTILINE)
check(warning >= 0 and first_step is not None and warning < first_step.start(),
      f"10^7 load steps: warning naming Load stepping/Number of load steps before step 1's line "
      f"(warning at {warning}, step 1 at {first_step.start() if first_step else None})")
check.finish()
