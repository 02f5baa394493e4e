#!/usr/bin/python3
"""The PVD time series of a run on two MPI ranks loads in ParaView (pvpython)
with every field the output promises (tests/check_pvd_fields.py). The contact
surface's own series (contact_surface.pvd) lists the same steps, holds the
contact surface only (the line y = 0, every node a contact node, status 0, 1
or 2) and its nodal contact pressure is the profile CSV's at every node; on the
axisymmetric Hertz ball on 2 ranks a rank without contact faces writes no piece (VTK's
readers report an empty one as an error)."""
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    text = f.read().replace("output-patin-elastic", "output")
text = text.replace("set Global refinements = 4", "set Global refinements = 2")
text = text.replace("set Number of load steps = 10", "set Number of load steps = 4")
sltest.run(executable, text, workdir, ranks=2)
pvpython = shutil.which("pvpython")
check(pvpython is not None, "pvpython is installed (package python3-paraview)")
if pvpython:
    script = os.path.join(os.path.dirname(__file__), "check_pvd_fields.py")
    result = subprocess.run([pvpython, script, os.path.join(workdir, "output"), "2"],
                            capture_output=True, text=True, timeout=600)
    print(result.stdout + result.stderr)
    check(result.returncode == 0, "the PVD loads in ParaView with the promised fields")


def pvd_files(path):
    return [(float(d.get("timestep")), d.get("file")) for d in ET.parse(path).getroot().iter("DataSet")]


def check_contact_surface(out, name):
    solution, surface = pvd_files(f"{out}/solution.pvd"), pvd_files(f"{out}/contact_surface.pvd")
    check([t for t, _ in solution] == [t for t, _ in surface] and len(surface) > 1,
          f"{name}: contact_surface.pvd lists the {len(solution)} steps of solution.pvd")
    reader = vtkXMLPUnstructuredGridReader()
    reader.SetFileName(os.path.join(out, surface[-1][1]))
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    data = grid.GetPointData()
    pressure = vtk_to_numpy(data.GetArray("contact_pressure_MPa")).astype(float)
    status = vtk_to_numpy(data.GetArray("contact_status")).astype(float)
    # the profile: every node of the contact surface, reference coordinates
    profile = {(round(row["x_mm"], 5), round(row["y_mm"], 5)): row["contact_pressure_MPa"]
               for row in sltest.last_profile(out)}
    keys = [(round(x, 5), round(y, 5)) for x, y in points[:, :2]]
    check(len(keys) > 0 and all(k in profile for k in keys) and set(keys) == set(profile),
          f"{name}: the last step's surface ({grid.GetNumberOfCells()} faces) has exactly the "
          f"{len(profile)} nodes of the contact surface")
    check(np.isin(status, (0, 1, 2)).all(), f"{name}: every node of the surface is a contact node "
          f"(status in {{0, 1, 2}}: {sorted(set(status.tolist()))})")
    scale = max(abs(v) for v in profile.values())
    worst = max(abs(p - profile.get(k, float("inf"))) for k, p in zip(keys, pressure))
    # the .vtu holds single precision (relative rounding 6e-8)
    check(worst <= 1e-6 * scale, f"{name}: nodal contact pressure of the surface = the profile's, "
          f"max difference {worst:.2e} MPa (peak {scale:.4g})")


check_contact_surface(os.path.join(workdir, "output"), "patin on 2 ranks")
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "hertz_axisymmetric.prm")) as f:
    hertz = f.read().replace("output-hertz-axisymmetric", "output")
# a contact zone small enough for one rank to hold all of it
hertz = hertz.replace("set Contact zone radius     = 20", "set Contact zone radius     = 5")
hertz += "\nsubsection Load stepping\n  set Number of load steps = 2\nend\n"
sltest.run(executable, hertz, os.path.join(workdir, "hertz"), ranks=2)
solution_pieces = [f for f in os.listdir(os.path.join(workdir, "hertz", "output"))
                   if f.startswith("solution_00002.") and f.endswith(".vtu")]
pieces = [f for f in os.listdir(os.path.join(workdir, "hertz", "output"))
          if f.startswith("contact_surface_00002.") and f.endswith(".vtu")]
with open(os.path.join(workdir, "hertz", "output", "contact_surface_00002.pvtu")) as f:
    listed = f.read().count("<Piece ")
check(len(solution_pieces) == 2 and len(pieces) == 1 and listed == 1,
      f"Hertz ball (axisymmetric) on 2 ranks, the contact zone on one: {len(solution_pieces)} pieces of the solution, "
      f"{len(pieces)} of the contact surface, {listed} listed (no empty piece)")
check_contact_surface(os.path.join(workdir, "hertz", "output"), "Hertz ball (axisymmetric) on 2 ranks")
check.finish()
