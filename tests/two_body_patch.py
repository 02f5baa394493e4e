#!/usr/bin/python3
"""Taylor-Papadopoulos contact patch test between two deformable bodies
(prm/contact_patch_test.prm on prm/meshes/contact_patch.geo): two stacked
10 x 5 mm elastic blocks of the same material with non-matching meshes on
their interface (8 graded cells along the lower block's top, 10 equal ones
along the upper block's bottom, no interior node in common), a uniform
pressure p = 100 MPa on the upper top, rollers under the lower block,
symmetry planes on the left, frictionless.

The exact solution is a uniform stress sigma_yy = -p in both blocks: its
displacement is linear, so it lies in the displacement space of every pair,
and the interface displacements of the two blocks coincide (same material),
so the gap is zero and the contact pressure is p at every point of the
interface. A contact discretisation that passes the patch test reproduces it
to solver tolerance, hence the bound 1e-8 relative (the Newton tolerance) on
the nodal contact pressure of the last load step and on the normal force
p L = 1000 N/mm. The stress (cell averages in the .vtu output, single
precision) is checked to be that uniform state in every cell of both blocks:
the master body receives the contact forces consistently.

Checked for the pair Q1/P1 and Q2/P1, with the slave on the finer side
(upper_bottom, the scene) and with the roles swapped (slave lower_top, the
coarser side), on 1 and 2 MPI ranks; and on the same blocks meshed with
triangles (the same interface nodes) for P1/P1, P2/P1 and P2/P2. Then the same
with `Complementarity = weighted` (the conditions per node on the weighted
gap), which must pass it as well, also with the dual multiplier bases
(Q1/P1 dual, Q2/P2 dual: the multiplier field of λ_j = p is p, since the
dual functions sum to one). Last the 3D patch test
(prm/contact_patch_test_3d.prm, hexahedra, 8 x 6 graded faces against 10 x 10):
the slave faces cut along the projected master faces, Q1/P1, Q2/P1 and Q2/P2,
both roles, 1 and 2 ranks, weighted and pointwise; sigma_zz = -p in every cell."""
import base64
import glob
import os
import re
import struct
import sys
import zlib
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
scene = sltest.read_prm(os.path.join(prm_dir, "contact_patch_test.prm"))
pressure, length = 100.0, 10.0
tolerance = 1e-8  # the solver tolerance: the exact solution is in the discrete space


def vtu_point_arrays(path):
    """The Float32 arrays of a .vtu written by deal.II (binary, zlib-compressed):
    name -> (components, values); the points under the name `points`."""
    with open(path) as f:
        text = f.read()
    arrays = {}
    for m in re.finditer(r'<DataArray type="Float32"(?: Name="([^"]*)")?(?: NumberOfComponents="(\d+)")? '
                         r'format="binary">\s*(\S+)\s*</DataArray>', text):
        name, components, data = m.group(1) or "points", int(m.group(2) or 1), m.group(3)
        # base64 header (uint32: blocks, block size, last block size, compressed sizes), then the blocks
        blocks = struct.unpack("<I", base64.b64decode(data[:8])[:4])[0]
        header_bytes = 4 * (3 + blocks)
        header_chars = 4 * ((header_bytes + 2) // 3)
        sizes = struct.unpack(f"<{3 + blocks}I", base64.b64decode(data[:header_chars])[:header_bytes])[3:]
        raw, position, values = base64.b64decode(data[header_chars:]), 0, b""
        for size in sizes:
            values += zlib.decompress(raw[position:position + size])
            position += size
        arrays[name] = (components, struct.unpack(f"<{len(values) // 4}f", values))
    return arrays


SLAVE = "set Contact boundary ids = upper_bottom"
MASTER = "set Master boundary ids  = lower_top"
PAIR = "set Finite element pair  = Q1/P1"
for entry in (SLAVE, MASTER, PAIR):
    if entry not in scene:
        raise SystemExit(f"FAIL: prm/contact_patch_test.prm has no '{entry}'")
swapped_scene = (scene.replace(SLAVE, "set Contact boundary ids = lower_top")
                 .replace(MASTER, "set Master boundary ids  = upper_bottom"))

# (pair, slave, ranks); the slave's vertices: 10 + 1 on upper_bottom, 8 + 1 on
# lower_top (one global refinement), plus the midsides for Q2
VTU = "\nsubsection Output\n  set Write vtu = true\nend\n"
cases = [("Q1/P1", "upper_bottom", 1), ("Q1/P1", "lower_top", 1),
         ("Q2/P1", "upper_bottom", 1), ("Q2/P1", "lower_top", 1),
         ("Q1/P1", "upper_bottom", 2), ("Q1/P1", "lower_top", 2),
         ("P1/P1", "upper_bottom", 1), ("P1/P1", "lower_top", 1), ("P1/P1", "upper_bottom", 2),
         ("P2/P1", "upper_bottom", 1), ("P2/P2", "lower_top", 2)]
cases = [case + ("pointwise",) for case in cases] + [
    ("Q1/P1", "upper_bottom", 1, "weighted"), ("Q1/P1", "lower_top", 2, "weighted"),
    ("Q2/P1", "upper_bottom", 2, "weighted"), ("Q2/P2", "lower_top", 1, "weighted"),
    ("P1/P1", "upper_bottom", 2, "weighted"), ("P2/P2", "lower_top", 1, "weighted"),
    ("Q1/P1 dual", "upper_bottom", 1, "weighted"), ("Q1/P1 dual", "lower_top", 2, "weighted"),
    ("Q2/P2 dual", "upper_bottom", 1, "weighted")]
WEIGHTED = "\nsubsection Contact\n  set Complementarity = weighted\nend\n"
# the P pairs on the same blocks meshed with triangles (Recombine removed: the same
# interface nodes, non-matching)
quadrilateral_geo = os.path.join(prm_dir, "meshes", "contact_patch.geo")
triangle_geo = os.path.join(workdir, "contact_patch_triangles.geo")
os.makedirs(workdir, exist_ok=True)
with open(quadrilateral_geo) as f, open(triangle_geo, "w") as out_geo:
    out_geo.write(re.sub(r"Recombine Surface\{\d+\};", "", f.read()))
def check_case(name, text, out, ranks, nodes, dim, measure):
    """Run one patch test and check it: every node of the slave in contact with
    the pressure p, the normal force p times the interface's measure, and the
    uniform stress sigma = -p e_n e_n (n the last axis) in every cell."""
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT + VTU, out, ranks=ranks, expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code != 0:
        print(log[-3000:])
        return
    profile = sltest.last_profile(os.path.join(out, "output"))
    check(len(profile) == nodes, f"{name}: {len(profile)} profile nodes, the slave has {nodes}")
    open_nodes = [row["x_mm"] for row in profile if row["status"] == 0]
    check(not open_nodes, f"{name}: every node in contact (open at x = {open_nodes})")
    error = max(abs(row["contact_pressure_MPa"] - pressure) for row in profile) / pressure
    worst = max(profile, key=lambda row: abs(row["contact_pressure_MPa"] - pressure))
    check(error < tolerance, f"{name}: max |p - {pressure:g}| / {pressure:g} = {error:.2e} "
          f"(worst at x = {worst['x_mm']:.3f}: {worst['contact_pressure_MPa']:.10g} MPa)")
    last = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]
    force = last["normal_force_N"]
    force_error = abs(force - pressure * measure) / (pressure * measure)
    check(force_error < tolerance, f"{name}: normal force {force:.8f} N{'/mm' if dim == 2 else ''} = p "
          f"{'L' if dim == 2 else 'A'}, relative error {force_error:.2e}")
    # every cell of both blocks: sigma_nn = -p, the other components 0; the
    # stress is written in single precision (relative rounding 6e-8), so the
    # bound is 1e-6 p, above the rounding and the solver tolerance
    files = glob.glob(os.path.join(out, "output", f"solution_{int(last['step']):05d}.*.vtu"))
    points, stress = [], []
    for path in files:
        arrays = vtu_point_arrays(path)
        points += arrays["points"][1]
        stress += arrays["stress_MPa"][1]
    normal = points[dim - 1::3]
    check(normal and min(normal) < 0 < max(normal),
          f"{name}: the .vtu output ({len(files)} file(s)) covers both blocks")
    nn = 4 * (dim - 1)  # sigma_yy (2D) or sigma_zz (3D) among the 3 x 3 components
    zero = (0, 1) if dim == 2 else (0, 1, 2, 4, 5)  # xx, xy (and xz, yy, yz)
    deviation = max([abs(stress[k + 9 * c]) for c in range(len(stress) // 9) for k in zero] +
                    [abs(s + pressure) for s in stress[nn::9]] or [float("inf")]) / pressure
    check(deviation < 1e-6, f"{name}: uniform stress sigma_nn = -p in both blocks, max deviation "
          f"{deviation:.1e} p over {len(normal)} output points")


for pair, slave, ranks, mode in cases:
    cells = 10 if slave == "upper_bottom" else 8
    nodes = cells + 1 if pair[1] == "1" else 2 * cells + 1
    pair_name = pair.replace("/", "").replace(" ", "-")
    text = (scene if slave == "upper_bottom" else swapped_scene).replace(PAIR, f"set Finite element pair  = {pair}")
    if pair.startswith("P"):
        text = text.replace(quadrilateral_geo, triangle_geo)
        if triangle_geo not in text:
            raise SystemExit("FAIL: the scene does not name prm/meshes/contact_patch.geo by its path")
    if mode == "weighted":
        text += WEIGHTED
    check_case(f"{pair}, slave {slave}, {ranks} rank(s), {mode}", text,
               os.path.join(workdir, f"{pair_name}-{slave}-np{ranks}-{mode}"), ranks, nodes, 2, length)

# 3D (prm/contact_patch_test_3d.prm): two 10 x 10 x 5 blocks, 8 x 6 graded faces
# below, 10 x 10 above, after one global refinement; the slave faces are cut
# along the projected master faces (3D segment integration). sigma_zz = -p.
scene_3d = sltest.read_prm(os.path.join(prm_dir, "contact_patch_test_3d.prm"))
for entry in (SLAVE, MASTER, PAIR, "set Complementarity      = weighted"):
    if entry not in scene_3d:
        raise SystemExit(f"FAIL: prm/contact_patch_test_3d.prm has no '{entry}'")
swapped_3d = (scene_3d.replace(SLAVE, "set Contact boundary ids = lower_top")
              .replace(MASTER, "set Master boundary ids  = upper_bottom"))
for pair, slave, ranks, mode in [("Q1/P1", "upper_bottom", 1, "weighted"), ("Q1/P1", "lower_top", 2, "weighted"),
                                 ("Q1/P1", "upper_bottom", 2, "pointwise"), ("Q2/P1", "lower_top", 1, "weighted"),
                                 ("Q2/P2", "upper_bottom", 1, "pointwise"), ("Q1/P1 dual", "lower_top", 2, "weighted"),
                                 ("Q2/P2 dual", "upper_bottom", 1, "weighted")]:
    faces = (10, 10) if slave == "upper_bottom" else (8, 6)
    degree = max(int(pair[1]), int(pair[4]))  # the profile has the nodes of the richer space
    nodes = (degree * faces[0] + 1) * (degree * faces[1] + 1)
    text = ((scene_3d if slave == "upper_bottom" else swapped_3d).replace(PAIR, f"set Finite element pair  = {pair}")
            .replace("set Complementarity      = weighted", f"set Complementarity = {mode}"))
    check_case(f"3D {pair}, slave {slave}, {ranks} rank(s), {mode}", text,
               os.path.join(workdir, f"3d-{pair.replace('/', '').replace(' ', '-')}-{slave}-np{ranks}-{mode}"),
               ranks, nodes, 3,
               length * length)
check.finish()
