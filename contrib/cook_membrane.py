#!/usr/bin/python3
"""Cook's membrane (prm/cook_membrane.prm): its mesh with n cells per edge and the displacement
it is measured by, shared by contrib/benchmark_cook.py and tests/near_incompressible.py."""
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def mesh_file(directory, n):
    """A .geo in `directory` that sets n cells per edge and includes prm/meshes/cook_membrane.geo."""
    path = os.path.join(directory, "cook.geo")
    with open(path, "w") as f:
        f.write(f"n = {n};\nInclude \"{os.path.join(ROOT, 'prm', 'meshes', 'cook_membrane.geo')}\";\n")
    return path


def corner_displacement(profile):
    """The vertical displacement (mm) of the corner (48, 44) from the rows of a profile-NNNNN.csv
    (numbers): the gap of that corner of the contact boundary, the lower edge, to the plane
    100 mm below it, minus 144 mm."""
    corner = min(profile, key=lambda r: abs(float(r["x_mm"]) - 48) + abs(float(r["y_mm"]) - 44))
    return float(corner["gap_mm"]) - 144.


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import tool_cli
    tool_cli.module_help(__doc__)
