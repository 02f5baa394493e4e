#!/usr/bin/env pvpython
"""Check that every array of every .vtu file under the given directories is finite.

Usage: pvpython tests/check_finite_vtu.py DIR [DIR ...]
Prints each file with a NaN or infinite value and exits 1 if there is one (or if
no .vtu file was found at all); exit 0 otherwise."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

files = [os.path.join(directory, name)
         for top in sys.argv[1:] for directory, _, names in os.walk(top)
         for name in names if name.endswith(".vtu")]
if not files:
    print("FAIL: no .vtu file under " + " ".join(sys.argv[1:]))
    sys.exit(1)
bad = []
for path in sorted(files):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    for data in (grid.GetPointData(), grid.GetCellData()):
        for i in range(data.GetNumberOfArrays()):
            values = vtk_to_numpy(data.GetArray(i))
            if not np.all(np.isfinite(values)):
                bad.append(f"{path}: {data.GetArrayName(i)}")
    if not np.all(np.isfinite(vtk_to_numpy(grid.GetPoints().GetData()))):
        bad.append(f"{path}: points")
for line in bad:
    print("FAIL: not finite in " + line)
print(f"{'FAIL' if bad else 'ok  '} {len(files)} .vtu files checked, {len(bad)} with non-finite values")
sys.exit(1 if bad else 0)
