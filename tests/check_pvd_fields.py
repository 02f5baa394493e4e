#!/usr/bin/env pvpython
"""Check the ParaView output of stabilized_lagrangian with ParaView's own reader.

Usage: pvpython tests/check_pvd_fields.py OUTPUT_DIR DIM
(reading needs no display, so no xvfb-run; pvpython comes with python3-paraview)

Checks: every file referenced by solution.pvd (and by its .pvtu records) exists;
more than one time step; at the last step the expected point arrays with their
number of components and the array `subdomain`; no NaN in any array at any step;
contact_status in {-1, 0, 1, 2} (-1 off the contact surface, and present); max
contact_pressure > 0. Exit 0 on success, 1 on failure.
"""
import os
import sys
import xml.etree.ElementTree as ET


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


if len(sys.argv) != 3 or sys.argv[2] not in ("2", "3"):
    print(__doc__)
    sys.exit(1)
directory, dim = sys.argv[1], int(sys.argv[2])
pvd = os.path.join(directory, "solution.pvd")
if not os.path.isfile(pvd):
    fail(f"{pvd} not found")

# ParaView only logs a missing file and carries on: list them all up front
try:
    records = [d.get("file") for d in ET.parse(pvd).iter("DataSet")]
    pieces = [os.path.join(os.path.dirname(r), p.get("Source"))
              for r in records if r.endswith(".pvtu")
              for p in ET.parse(os.path.join(directory, r)).iter("Piece")]
except (ET.ParseError, OSError) as error:
    fail(f"cannot read the records of {pvd}: {error}")
missing = [f for f in records + pieces if not os.path.isfile(os.path.join(directory, f))]
if missing:
    fail(f"{len(missing)} file(s) referenced by {pvd} missing: {', '.join(missing[:5])}")
print(f"ok   {len(records)} records and {len(pieces)} pieces referenced by {pvd} exist")

import numpy as np
from paraview import servermanager
from paraview.simple import MergeBlocks, PVDReader
from vtk.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

reader = PVDReader(FileName=pvd)
times = reader.TimestepValues
times = [times] if isinstance(times, float) else list(times)  # a single step comes as a bare float
if len(times) < 2:
    fail(f"{len(times)} time step(s), expected more than one")
print(f"ok   {len(times)} time steps, t = {times[0]:g} .. {times[-1]:g}")

merged = MergeBlocks(Input=reader)  # one grid whatever the number of MPI pieces


def fetch(time):
    """The data at `time`; a reader error (e.g. an array missing from one piece) is a failure:
    the reader only logs it and fills the array with zeros. pvpython prints through the
    output window too, so it is swapped only around the read."""
    original, capture = vtkOutputWindow.GetInstance(), vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(capture)
    try:
        merged.UpdatePipeline(time)
        data = dsa.WrapDataObject(servermanager.Fetch(merged))
    finally:
        vtkOutputWindow.SetInstance(original)
    if "ERROR" in capture.GetOutput():
        fail(f"reading t = {time:g}: {' '.join(capture.GetOutput().split())[:400]}")
    return data


# deal.II's VTU writer pads vectors to 3 and tensors to 3x3 components, with zeros
vector, tensor = (dim, 3), (dim * dim, 9)
expected = {"displacement_mm": vector, "stress_MPa": tensor, "von_mises_stress_MPa": (1,),
            "contact_pressure_MPa": (1,), "tangential_traction_MPa": vector, "gap_mm": (1,),
            "slip_increment_mm": vector, "contact_status": (1,)}
last = fetch(times[-1])
if last.GetNumberOfPoints() == 0:
    fail(f"the last step (t = {times[-1]:g}) has no points")
z = np.asarray(last.Points)[:, 2]
if (np.ptp(z) > 0) != (dim == 3):
    fail(f"the mesh is {'3' if np.ptp(z) > 0 else '2'}D (z from {z.min():g} to {z.max():g}), DIM = {dim}")
print(f"ok   {dim}D mesh, {last.GetNumberOfPoints()} points, {last.GetNumberOfCells()} cells at the last step")
for name, sizes in expected.items():
    if name not in last.PointData.keys():
        fail(f"point array '{name}' missing at the last step (found: {', '.join(last.PointData.keys())})")
    values = np.asarray(last.PointData[name]).reshape(last.GetNumberOfPoints(), -1)
    n = values.shape[1]
    if n not in sizes:
        fail(f"'{name}' has {n} components, expected {' or '.join(map(str, sizes))}")
    if n > sizes[0]:  # padded: everything outside the first dim (x dim) entries must be zero
        used = list(range(dim)) if n == 3 else [3 * i + j for i in range(dim) for j in range(dim)]
        if np.any(np.delete(values, used, axis=1)):
            fail(f"'{name}': the components padding it to {n} are not zero")
    print(f"ok   point array {name:20s} {n} component(s)" + (f", zero beyond the first {sizes[0]}" if n > sizes[0] else ""))

# The program adds `subdomain` as a cell vector, but deal.II's VTU writer stores every
# field as point data (each cell has its own copy of its vertices).
where = "cell" if "subdomain" in last.CellData.keys() else "point" if "subdomain" in last.PointData.keys() else None
if where is None:
    fail("array 'subdomain' missing (neither cell nor point data) at the last step")
print(f"ok   {where} array subdomain")

for time in times:
    data = fetch(time)
    for kind, arrays in (("point", data.PointData), ("cell", data.CellData)):
        for name in arrays.keys():
            if np.isnan(np.asarray(arrays[name])).any():
                fail(f"{kind} array '{name}' contains NaN at t = {time:g}")
    if "contact_status" in data.PointData.keys():
        status = np.unique(np.asarray(data.PointData["contact_status"]))
        if not np.isin(status, (-1, 0, 1, 2)).all():
            fail(f"contact_status takes values {status} at t = {time:g}, expected only -1 (not a contact "
                 "node), 0 (open), 1 (stick), 2 (slip)")
        if -1 not in status:
            fail(f"contact_status is never -1 at t = {time:g}: the nodes off the contact surface "
                 "are not told from open ones")
print(f"ok   no NaN in any array and contact_status in {{-1, 0, 1, 2}} at all {len(times)} steps")

p_max = np.max(last.PointData["contact_pressure_MPa"])
if not p_max > 0:
    fail(f"max contact_pressure = {p_max:g} at the last step, expected > 0")
print(f"ok   max contact_pressure = {p_max:g} > 0 at the last step")
print("PASS")
