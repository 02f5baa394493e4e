#!/usr/bin/python3
"""The PVD time series of a run on two MPI ranks loads in ParaView (pvpython)
with every field the output promises (tests/check_pvd_fields.py). The contact
surface's own series (contact_surface.pvd) lists the same steps, holds the
contact surface only (the line y = 0, every node a contact node, status 0, 1
or 2) and its nodal contact pressure is the profile CSV's at every node; on the
axisymmetric Hertz ball on 2 ranks a rank without contact faces writes no piece (VTK's
readers report an empty one as an error).

contrib/render_pvd.py: on two cylinders touching at a point (prm/two_cylinders.prm),
the contact strip it draws holds the slave's nodes only (the master's node at the
same place, pressure 0, made a notch where the pressure is largest), checked on the
strip's nodes and on the picture's colours; its force label says N/mm in plane
strain, N in an axisymmetric model; it reads the output under the names of schema 1
too (CHANGELOG.md: VTU fields without units, plane strain forces `_N`)."""
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
hertz_statistics = sltest.run_output.read_csv(os.path.join(workdir, "hertz", "output", "statistics.csv"))
label = sltest.run_output.force_label(hertz_statistics[-1])
check(label.endswith(" N"), f"contrib/render_pvd.py's force label of an axisymmetric run: '{label}' (N)")


def read_grid(path):
    reader = vtkXMLPUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def rendered(output, png, *arguments):
    """contrib/render_pvd.py on an output directory (ParaView, a virtual display): whether it wrote png."""
    if not pvpython or not shutil.which("xvfb-run"):
        check(False, "pvpython and xvfb-run are installed (packages python3-paraview, xvfb)")
        return False
    # a virtual display that does not come up ("bad X server connection": one start in a few on
    # a loaded machine) is no fault of the picture: the render is tried again on a new display
    for attempt in range(3):
        result = subprocess.run(["xvfb-run", "-a", pvpython, render_tool, output, "--output", png, *arguments],
                                capture_output=True, text=True, timeout=600)
        if result.returncode == 0 or "bad X server connection" not in result.stderr:
            break
        print(f"      (the virtual display did not come up; render attempt {attempt + 2})")
    check(result.returncode == 0 and os.path.exists(png),
          f"render_pvd.py {os.path.basename(output)} {' '.join(arguments)}: exit code {result.returncode}"
          + (f", {result.stderr.strip()[-400:]}" if result.returncode else ""))
    return result.returncode == 0 and os.path.exists(png)


def strip_colours(png):
    """The columns of the picture's coloured pixels (the contact strip: saturated, unlike the
    greys of the bodies, the black text and the white background; the colour bar, at the right,
    left out), each with its reddest pixel's red and blue."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :int(0.85 * width), :3]
    pixels = pixels.astype(int)
    saturated = pixels.max(2) - pixels.min(2) > 80
    columns = np.nonzero(saturated.any(0))[0]
    return columns, [pixels[saturated[:, c], c, 0].max() for c in columns]


# two bodies touching at a point (prm/two_cylinders.prm, pressed only): the slave's and the
# master's nodes there are at one place; contrib/render_pvd.py draws the contact strip of the
# slave's nodes only, so that its pressure has no notch of 0 where it is largest, and labels the
# force of the plane strain run in N/mm
render_tool = os.path.join(os.path.dirname(__file__), "..", "contrib", "render_pvd.py")
cylinders = sltest.read_prm(os.path.join(os.path.dirname(__file__), "..", "prm", "two_cylinders.prm"))
cylinders = cylinders.replace("output-two-cylinders", "output").replace(
    "set End time             = 1", "set End time             = 0.5").replace(
    "set Number of load steps = 8", "set Number of load steps = 2")
two_bodies = os.path.join(workdir, "two_cylinders")
sltest.run(executable, cylinders, two_bodies)
out = os.path.join(two_bodies, "output")
grid = read_grid(os.path.join(out, "solution_00002.pvtu"))
points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
pressure = vtk_to_numpy(grid.GetPointData().GetArray("contact_pressure_MPa")).astype(float)
status = vtk_to_numpy(grid.GetPointData().GetArray("contact_status")).astype(float)
profile = {(round(row["x_mm"], 5), round(row["y_mm"], 5)) for row in sltest.last_profile(out)}
marked = [(round(x, 5), round(y, 5)) in profile for x, y in points[:, :2]]
on_surface = np.array(sltest.run_output.on_contact_surface(marked, status))
at_origin = np.abs(points).max(1) < 1e-9
check(at_origin.any() and (status[at_origin] == -1).any() and (status[at_origin] >= 0).any(),
      f"two cylinders: slave and master nodes at the origin (status {sorted(set(status[at_origin].tolist()))})")
check(on_surface[at_origin].sum() == (status[at_origin] >= 0).sum() and (pressure[at_origin & on_surface] > 0).all(),
      f"two cylinders: of the {at_origin.sum()} points at the origin, the slave's "
      f"({(status[at_origin] >= 0).sum()}) are on the drawn surface, pressure "
      f"{sorted(set(pressure[at_origin & on_surface].tolist()))} MPa")
cells = [[grid.GetCell(c).GetPointId(k) for k in range(grid.GetCell(c).GetNumberOfPoints())]
         for c in range(grid.GetNumberOfCells())]
strip = sltest.run_output.contact_strip(cells, on_surface, False)
ends = np.unique(np.array(strip, dtype=int).ravel()) if strip else np.array([], dtype=int)
peak = pressure[ends].max() if len(ends) else 0.0
central = ends[np.abs(points[ends, 0]) <= 0.25 * np.abs(points[ends[pressure[ends] > 0], 0]).max()] if len(ends) else ends
check(len(strip) > 10 and (status[ends] >= 0).all() and len(central) and pressure[central].min() > 0.9 * peak,
      f"two cylinders: the drawn strip ({len(strip)} edges) has slave nodes only and no notch: "
      f"central pressure {pressure[central].min() if len(central) else float('nan'):.4g} .. {peak:.4g} MPa")
statistics = sltest.run_output.read_csv(os.path.join(out, "statistics.csv"))
label = sltest.run_output.force_label(statistics[-1])
check(label.endswith(" N/mm") and f"{statistics[-1]['normal_force_N_per_mm']:.4g}" in label,
      f"render_pvd.py's force label of a plane strain run: '{label}' (N/mm)")
png = os.path.join(two_bodies, "pressure.png")
if rendered(out, png, "--view", "contact"):
    columns, red = strip_colours(png)
    # the strip's middle third, around the peak: the colours of the top of the bar (red, magenta)
    middle = [r for c, r in zip(columns, red) if abs(c - columns.mean()) <= np.ptp(columns) / 6] if len(columns) else []
    check(len(columns) > 100 and middle and min(middle) > 150,
          f"two cylinders, the picture: {len(columns)} columns of the strip, least red in its middle third "
          f"{min(middle) if middle else None} (a notch of 0 would be blue)")

# the same output under the names of schema 1 (CHANGELOG.md): VTU fields without units, plane
# strain forces `_N`, no schema_version; render_pvd.py reads them too
old = os.path.join(two_bodies, "schema_1")
shutil.rmtree(old, ignore_errors=True)
shutil.copytree(out, old)
for name in os.listdir(old):
    path = os.path.join(old, name)
    if name.endswith(".vtu"):
        with open(path, "rb") as f:
            data = f.read()
        for old_name, new_name in sltest.run_output.RENAMED_VTU_FIELDS.items():
            data = data.replace(f'Name="{new_name}"'.encode(), f'Name="{old_name}"'.encode())
        with open(path, "wb") as f:
            f.write(data)
    elif name.endswith(".csv"):
        with open(path) as f:
            header, rest = f.read().split("\n", 1)
        header = ",".join(c for c in header.replace("_N_per_mm", "_N").split(",") if c != "schema_version")
        with open(path, "w") as f:
            f.write(header + "\n" + rest)
check("displacement_mm" not in open(os.path.join(old, "solution_00002.0.vtu"), errors="replace").read(),
      "the schema 1 copy has no displacement_mm")
rendered(old, os.path.join(two_bodies, "schema_1.png"), "--view", "contact")
check.finish()
