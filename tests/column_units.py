#!/usr/bin/python3
"""Forces in the output carry their unit in their names: N in 3D and in an axisymmetric model
(totals over the revolution), N_per_mm in plane strain (per unit thickness), in
statistics.csv, iterations.csv and refinement_cycles.csv, and N/mm in the step lines of a plane
strain run. The scene is tests/scenes/eccentric_plate.prm: it has every kind of force column
but the zones' (contact force, normal and tangential force, a rigid plate's force, the residual,
the reaction of a single-node Dirichlet condition). run_summary.csv starts with the output
schema's version (`schema_version`), the one contrib/run_output.py reads and CHANGELOG.md lists."""
import csv
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "CHANGELOG.md")) as f:
    changelog = f.read()


def scene(dim, axisymmetric=False):
    text = sltest.scene("eccentric_plate", DIM=dim, ROTATION="guided", POINT="",
                        SUBDIVISIONS="2, 1" if dim == 2 else "2, 2, 1", REFINEMENTS=1,
                        ORIGIN="0, 0" if dim == 2 else "0, 0, 0", UP="0, 1" if dim == 2 else "0, 0, 1",
                        COMPONENTS="y" if dim == 2 else "z",
                        FORCE="0; -10*t" if dim == 2 else "0; 0; -10*t")
    # a vertex of the top held sideways (a reaction column) and two refinement cycles
    # (refinement_cycles.csv)
    text += sltest.nested_set("Adaptive refinement/Cycles", 1)
    text += ("subsection Boundary conditions\n  subsection Dirichlet middle\n"
             f"    set Point = {'10, 10' if dim == 2 else '0, 0, 10'}\n    set Components = x\n  end\nend\n")
    if axisymmetric:
        text = text.replace("set Model = block\n", "set Axisymmetric = true\n  set Model = block\n").replace(
            "    set Length             = 20\n", "    set Length             = 20\n    set Left side = 0\n")
    return text


for name, dim, axisymmetric, unit in (("plane strain", 2, False, "N_per_mm"), ("3D", 3, False, "N"),
                                      ("axisymmetric", 2, True, "N")):
    out = os.path.join(workdir, name.replace(" ", "_"))
    code, log = sltest.run(executable, scene(dim, axisymmetric), out)
    headers = {}
    for table in ("statistics.csv", "iterations.csv", "refinement_cycles.csv"):
        path = os.path.join(out, "output", table)
        if not os.path.exists(path):
            path = os.path.join(out, "output", "cycle-1", table)
        with open(path) as f:
            headers[table] = next(csv.reader(f))
    forces = [c for h in headers.values() for c in h if "force" in c or "residual" in c or "reaction" in c]
    forces = [c for c in forces if "scaled" not in c]
    wrong = [c for c in forces if not c.endswith("_" + unit)]
    check(len(forces) >= 8 and not wrong,
          f"{name}: the {len(forces)} force columns end in _{unit} ({', '.join(sorted(set(forces))[:4])}, ...)"
          + (f"; not: {wrong}" if wrong else ""))
    summary = os.path.join(out, "output", "run_summary.csv")
    rows = []
    if os.path.exists(summary):
        with open(summary) as f:
            rows = list(csv.reader(f))
    version = sltest.run_output.SCHEMA_VERSION
    check(len(rows) == 2 and rows[0][0] == "schema_version" and rows[1][0] == str(version)
          and f"\n| {version} |" in changelog,
          f"{name}: run_summary.csv starts with {rows[0][0] + ' = ' + rows[1][0] if len(rows) == 2 else None} "
          f"(contrib/run_output.py's {version}, a row of CHANGELOG.md)")
    step_lines = [line for line in log.splitlines() if line.startswith("step ")]
    expected = " N/mm, scaled" if unit == "N_per_mm" else " N, scaled"
    check(step_lines and all(expected in line for line in step_lines),
          f"{name}: the step lines give the residual in {expected.split(',')[0].strip()}")
check.finish()
