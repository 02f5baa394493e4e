#!/usr/bin/python3
"""Scenes from Gmsh: prm/gmsh_block.prm takes the patin's mesh from
prm/meshes/block.geo (meshed by the Gmsh library at start-up) and names its
boundaries by the physical groups.

Checks: the Gmsh patin gives the built-in patin's loop counts and forces (the
two meshes are the same 32 x 16 quadrilaterals), on 1 and 2 MPI ranks; a 3D
block of hexahedra (prm/meshes/block3d.geo) pressed by a uniform pressure on
its face named `top` has the contact pressure p on its face named `bottom`; a
mistyped group name in the contact or a boundary-condition entry stops the run
with exit 1 and a message naming the entry and listing the groups the file has;
a missing mesh file is refused with a message; a mesh of triangles runs with
the P1/P1 pair and is refused with a Q pair, by a message naming the P pairs;
two bodies of tetrahedra are refused (the master surface holds line and
quadrilateral faces) with the same message whether their surfaces are given by
name or by id; a .msh with a self-intersecting (bow-tie) quadrilateral is
refused with a message naming the cell's place, not run into a singular
system (an inverted cell, its vertices in the other order, deal.II's GridIn
turns round itself); a shipped scene `include`d from another folder finds its
mesh beside the scene's file (prm/meshes/), not beside the including file; a
3D .geo in a 2D run, and a 2D one in a 3D run, are refused naming the entry
and `Dimension`, not meshed in the run's dimension."""
import os
import re
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
gmsh_scene = sltest.read_prm(os.path.join(prm_dir, "gmsh_block.prm"))
builtin_scene = sltest.read_prm(os.path.join(prm_dir, "patin_elastic.prm"))

runs = {}
for name, text, ranks in (("built-in", builtin_scene, 1), ("gmsh", gmsh_scene, 1), ("gmsh, 2 ranks", gmsh_scene, 2)):
    out = os.path.join(workdir, name.replace(" ", "_").replace(",", ""))
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, ranks=ranks, expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code == 0:
        runs[name] = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    else:
        print(log[-2000:])
if len(runs) == 3:
    reference = runs["built-in"]
    for name in ("gmsh", "gmsh, 2 ranks"):
        rows = runs[name]
        counts = ("geometry_iterations", "friction_iterations", "status_iterations", "newton_iterations",
                  "points_in_contact", "points_stick", "points_slip")
        check(len(rows) == len(reference) and all(a[c] == b[c] for a, b in zip(rows, reference) for c in counts),
              f"{name}: the built-in patin's loop and point counts in {len(rows)} steps")
        worst = max(abs(a[f] - b[f]) / abs(b["normal_force_N"]) for a, b in zip(rows, reference)
                    for f in ("normal_force_N", "tangential_force_N", "contact_force_x_N", "contact_force_y_N"))
        check(worst < 1e-9, f"{name}: the built-in patin's forces (max difference {worst:.1e} of F_n)")

# 3D: hexahedra from an extruded .geo, frictionless, symmetry planes by name
block3d = os.path.join(prm_dir, "meshes", "block3d.geo")
text3d = sltest.gmsh_mesh(3, block3d) + """subsection Obstacle
  subsection plane
    set Point = 0, 0, 0
    set Normal = 0, 0, 1
  end
end
subsection Contact
  set Contact boundary ids = bottom
  subsection Friction law
    subsection Coulomb
      set Friction coefficient = @MU@
    end
  end
end
subsection Boundary conditions
  subsection Dirichlet 1
    set Boundary id = x min
    set Components = x
  end
  subsection Dirichlet 2
    set Boundary id = y min
    set Components = y
  end
  subsection Neumann 1
    set Boundary id = top
    subsection Traction
      set Function expression = 0; 0; -100*t
      set Variable names = x,y,z,t
    end
  end
end
"""
# with friction, the vertices on the symmetry planes have a prescribed tangential
# displacement: their friction multiplier is constrained (tests/stick_slip.py)
for ranks, mu in ((1, 0), (2, 0), (1, 0.3), (2, 0.3)):
    out = os.path.join(workdir, f"block3d-np{ranks}-mu{mu}")
    code, log = sltest.run(executable, text3d.replace("@MU@", str(mu)) + sltest.QUIET_OUTPUT, out, ranks=ranks,
                           expect_success=False)
    check(code == 0, f"3D Gmsh block, mu = {mu}, on {ranks} rank(s): exit code {code}")
    if code != 0:
        print(log[-2000:])
        continue
    last = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]
    force = last["normal_force_N"]
    pressures = [row["contact_pressure_MPa"] for row in sltest.last_profile(os.path.join(out, "output"))]
    check(abs(force - 100 * 100 * 50) < 1e-8 * 100 * 100 * 50,
          f"3D Gmsh block, mu = {mu}, on {ranks} rank(s): normal force {force:.6f} N = p x area")
    check(last["tangential_force_N"] <= mu * force * (1 + 1e-8),
          f"3D Gmsh block, mu = {mu}: F_t = {last['tangential_force_N']:.4f} N <= mu F_n")
    if mu > 0:
        continue
    check(pressures and max(abs(p - 100) for p in pressures) < 1e-8 * 100,
          f"3D Gmsh block, mu = 0, on {ranks} rank(s): contact pressure = p at the {len(pressures)} "
          "profile nodes")

groups = ["'bottom'", "'left'", "'right'", "'top'", "'block'"]
for entry, old, new in (("Contact/Contact boundary ids", "set Contact boundary ids = bottom",
                         "set Contact boundary ids = bottm"),
                        ("Boundary conditions/Dirichlet 1/Boundary id", "set Boundary id = top",
                         "set Boundary id = Top")):
    text = gmsh_scene.replace(old, new)
    check(text != gmsh_scene, f"the scene has '{old}'")
    code, log = sltest.run(executable, text, os.path.join(workdir, "mistyped"), expect_success=False)
    check(code == 1 and entry in log and all(g in log for g in groups),
          f"mistyped group in {entry}: exit {code}, the message names the entry and lists the groups")
    print("      " + log.strip().splitlines()[-1][:300])

code, log = sltest.run(executable, gmsh_scene.replace("block.geo", "no_such_file.geo"),
                       os.path.join(workdir, "missing"), expect_success=False)
check(code == 1 and "Geometry/gmsh/Mesh file" in log and "cannot open" in log,
      f"missing mesh file: exit {code}, the message names the entry")

# the same block with triangles: Recombine removed
with open(os.path.join(prm_dir, "meshes", "block.geo")) as f:
    triangles = f.read().replace("Recombine Surface{1};", "")
os.makedirs(os.path.join(workdir, "triangles"), exist_ok=True)
geo = os.path.join(workdir, "triangles", "triangles.geo")
with open(geo, "w") as f:
    f.write(triangles)
text = gmsh_scene.replace(os.path.join(prm_dir, "meshes", "block.geo"), geo)
check(geo in text, "the scene names the triangle mesh")
code, log = sltest.run(executable, text, os.path.join(workdir, "triangles"), expect_success=False)
check(code == 1 and "Finite element pair = Q1/P1 is for quadrilaterals" in log and "P1/P1" in log,
      f"a mesh of triangles with the Q1/P1 pair: exit {code}, refused with a message naming the P pairs")
text = text.replace("set Finite element pair  = Q1/P1", "set Finite element pair  = P1/P1")
check("P1/P1" in text, "the scene asks for P1/P1")
code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, os.path.join(workdir, "triangles-p1"),
                       expect_success=False)
check(code == 0, f"the same mesh of triangles with P1/P1: exit {code}")

# two bodies of tetrahedra: the master surface holds line and quadrilateral faces only, so the
# scene is refused with the same message whether its surfaces are given by name or by id (by
# name, the master surface was built from triangles and the run died of a segfault)
tetrahedra_geo = """SetFactory("OpenCASCADE");
Geometry.AutoCoherence = 0;  // two bodies: the interface nodes distinct
Mesh.CharacteristicLengthMax = 2.5;
Box(1) = {0, 0, -5, 10, 10, 5};  // surfaces 1 to 6: x min, x max, y min, y max, z min, z max
Box(2) = {0, 0, 0, 10, 10, 5};   // surfaces 7 to 12
Physical Surface("blk_bottom", 1) = {5};
Physical Surface("blk_contact", 2) = {6};
Physical Surface("cyl_contact", 7) = {11};
Physical Surface("cyl_top", 8) = {12};
Physical Volume("block", 1) = {1};
Physical Volume("punch", 2) = {2};
"""
os.makedirs(os.path.join(workdir, "tetrahedra"), exist_ok=True)
geo = os.path.join(workdir, "tetrahedra", "two_bodies.geo")
with open(geo, "w") as f:
    f.write(tetrahedra_geo)


def two_tetrahedral_bodies(slave, master, bottom, top):
    return sltest.gmsh_mesh(3, geo) + f"""subsection Contact
  set Contact boundary ids = {slave}
  set Master boundary ids  = {master}
  set Finite element pair  = P1/P1
  set Contact quadrature   = Gauss
end
subsection Boundary conditions
  subsection Dirichlet bottom
    set Boundary id = {bottom}
    set Components  = x, y, z
  end
  subsection Neumann top
    set Boundary id = {top}
    subsection Traction
      set Function expression = 0; 0; -10*t
      set Variable names      = x,y,z,t
    end
  end
end
subsection Load stepping
  set Number of load steps = 1
end
"""


for name, surfaces in (("by name", ("cyl_contact", "blk_contact", "blk_bottom", "cyl_top")),
                       ("by id", (7, 2, 1, 8))):
    code, log = sltest.run(executable, two_tetrahedral_bodies(*surfaces) + sltest.QUIET_OUTPUT,
                           os.path.join(workdir, "tetrahedra", name.replace(" ", "_")),
                           expect_success=False)
    check(code == 1 and "Master boundary ids" in log and "master surface of triangle faces" in log,
          f"two bodies of tetrahedra, surfaces {name}: exit {code} (a signal is negative), refused "
          f"with the master surface's message")
    if code != 1:
        print(log[-1500:])

# a cell whose Jacobian changes sign (a bow-tie: the second quadrilateral's last two nodes swapped)
QUADS_WITH_A_BOW_TIE = """$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
2
1 3 2 1 1 1 2 5 4
2 3 2 1 1 2 3 5 6
$EndElements
"""
for name, scene, mesh, expected in (
        ("bow-tie quadrilateral", gmsh_scene, QUADS_WITH_A_BOW_TIE,
         "the cell of the mesh at (1.5 0.5) is self-intersecting (a bow-tie)"),):
    directory = os.path.join(workdir, name.replace(" ", "_"))
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "cells.msh"), "w") as f:
        f.write(mesh)
    text = re.sub(r"set Mesh file\s*=.*", "set Mesh file = cells.msh", scene)
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, directory, expect_success=False)
    check(code == 1 and expected in log, f"{name}: exit {code}, refused naming the cell")
    if code != 1 or expected not in log:
        print(log[-1500:])

# prm/gmsh_block.prm (relative `meshes/block.geo`) included from the work directory
directory = os.path.join(workdir, "included_scene")
code, log = sltest.run(executable, f"include {os.path.join(prm_dir, 'gmsh_block.prm')}\n" +
                       sltest.nested_set("Load stepping/Number of load steps", 1) +
                       sltest.QUIET_OUTPUT, directory, expect_success=False)
check(code == 0, f"a scene included from another folder finds its mesh beside it: exit {code}")
if code != 0:
    print(log[-1500:])
# a geometry of the other dimension: the 3D block in a 2D run, the 2D block in a 3D run
block3d_scene = sltest.read_prm(os.path.join(prm_dir, "gmsh_block_3d.prm"))
for name, text, geo, expected in (
        ("3D geometry, 2D run", gmsh_scene, "block3d.geo", "its geometry is 3D"),
        ("2D geometry, 3D run", block3d_scene, "block.geo", "its geometry is 2D")):
    text = re.sub(r"set Mesh file\s*=.*", f"set Mesh file = {os.path.join(prm_dir, 'meshes', geo)}",
                  text)
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT,
                           os.path.join(workdir, name.replace(" ", "_").replace(",", "")),
                           expect_success=False)
    check(code == 1 and expected in log and "Geometry/gmsh/Mesh file" in log and "Dimension" in log,
          f"{name}: exit {code}, refused naming the entry, the dimensions and `Dimension`")
    if code != 1 or expected not in log:
        print(log[-1500:])
check.finish()
