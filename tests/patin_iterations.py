#!/usr/bin/python3
"""The three patin scenes of the seed paper (prm/patin_elastic.prm,
prm/patin_neo_hookean.prm, prm/patin_elastoplastic.prm) run to the end on a
coarse mesh, and the iteration count of every loop (iterations.csv: one row per
Newton loop, with its geometry, friction and status iteration numbers and its
status changes) equals the stored one in tests/reference/ (numdiff, no
tolerance: counts are integers, and every decision the loops take is away from
round-off, tests/reproducibility.py), so any change in convergence behaviour
shows up here; and the forces and the last contact profile equal the stored
ones within the tolerance the Newton criterion implies (check_values). Set
SL_UPDATE_REFERENCE=1 to rewrite the references after a change
that is meant to alter them."""
import csv
import os
import shutil
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
check = sltest.Checker()
numdiff = shutil.which("numdiff")
check(numdiff is not None, "numdiff is installed")

def write_or_read(name, header, rows):
    """The reference rows of tests/reference/<name> (rewritten with SL_UPDATE_REFERENCE=1)."""
    path = os.path.join(here, "reference", name)
    if os.environ.get("SL_UPDATE_REFERENCE") == "1":
        with open(path, "w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(header)
            writer.writerows([[repr(v) for v in r] for r in rows])
    with open(path) as f:
        return [[float(v) for v in r] for r in list(csv.reader(f))[1:]]


def check_values(material, output):
    """Forces per step and the last step's nodal contact pressure and tangential traction,
    each column within 1e-6 of its largest value. The scaled Newton criterion leaves a force
    imbalance of at most 1e-8 of the largest nodal force at every node; summed over the 17
    contact nodes of this mesh it stays below 1e-6 of the contact force, and a nodal pressure moves by less than 1e-6 of the peak. Round-off (1e-12 here,
    tests/reproducibility.py) is far below; a change of the discrete solution is far above."""
    steps = sltest.read_csv(output + "/statistics.csv")
    columns = ["time", "normal_force_N", "tangential_force_N"]
    forces = [[r[c] for c in columns] for r in steps]
    profile_columns = ["x_mm", "contact_pressure_MPa", "tangential_traction_x_MPa"]
    profile = [[r[c] for c in profile_columns] for r in sltest.last_profile(output)]
    for name, header, rows in ((f"patin_{material}_forces.csv", columns, forces),
                               (f"patin_{material}_profile.csv", profile_columns, profile)):
        reference = write_or_read(name, header, rows)
        worst = 0.
        if len(reference) == len(rows):
            for c in range(len(header)):
                scale = max(abs(r[c]) for r in reference) or 1.
                worst = max([worst] + [abs(a[c] - b[c]) / scale for a, b in zip(rows, reference)])
        check(len(reference) == len(rows) and worst <= 1e-6,
              f"{material}: {header[1]}... equal tests/reference/{name} to {worst:.1e} "
              f"of each column's scale (<= 1e-6)")


for material in ("elastic", "neo_hookean", "elastoplastic"):
    with open(os.path.join(here, "..", "prm", f"patin_{material}.prm")) as f:
        text = f.read()
    text = text.replace("set Global refinements = 4", "set Global refinements = 3")
    out = f"{workdir}/{material}"
    if not sltest.run_checked(executable, text, out, check, material):
        continue
    counts = os.path.join(out, "iteration_counts.csv")
    with open(os.path.join(out, "output", "iterations.csv")) as f, open(counts, "w", newline="") as g:
        writer = csv.writer(g, lineterminator="\n")
        for row in csv.reader(f):
            writer.writerow(row[:5] + row[7:])  # every column but the two residuals
    reference = os.path.join(here, "reference", f"patin_{material}_iterations.csv")
    if os.environ.get("SL_UPDATE_REFERENCE") == "1":
        shutil.copy(counts, reference)
        print(f"updated {reference}")
    # forces of every step and the last contact profile against their references,
    # with tolerances that follow from the Newton criterion (see check_values)
    check_values(material, out + "/output")
    if numdiff is None:
        continue
    result = subprocess.run([numdiff, "--absolute-tolerance=0", "--relative-tolerance=0",
                             "--separators=,\n", reference, counts], capture_output=True, text=True)
    total = sum(int(r["newton_iterations"]) for r in csv.DictReader(open(counts)))
    check(result.returncode == 0,
          f"{material}: iteration counts equal tests/reference/patin_{material}_iterations.csv "
          f"({total} Newton iterations)")
    if result.returncode != 0:
        print(result.stdout[-3000:])
check.finish()
