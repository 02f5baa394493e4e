#!/usr/bin/python3
"""A block pressed by a uniform pressure p onto a frictionless rigid plane,
meshed with distorted quadrilaterals (2D) and hexahedra (3D): every vertex not
on an edge of the block is moved at random by up to 20 % of h, those of a face
within the face's plane, so the contact face's cells are general
quadrilaterals, not parallelograms. The exact solution (uniaxial stress,
linear displacement) is in every displacement space, and the volume and load
integrals are exact on these cells, so the written contact pressure must be p
at every node, up to the solver's round-off, with the default (nodal,
Gauss-Lobatto) contact quadrature and with Gauss: the nodal weights must be
the consistent ∫ℓ_a dΓ, not the lumped w_a J(x_a) (doc/formulation.md,
"Contact quadrature"). The normal force must be p times the area."""
import itertools
import os
import random
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
pressure = 100.0
length, height = 40.0, 20.0  # the block is [0, L]^(dim-1) x [0, H]
physical = {"x min": 1, "x max": 2, "bottom": 3, "top": 4, "y min": 5, "y max": 6}


def distorted_block(dim, n, seed):
    """An ASCII Gmsh 2.2 mesh of the block with n cells per side (n/2 in the
    height), its vertices moved as the docstring says."""
    rng = random.Random(seed)
    counts = [n] * (dim - 1) + [n // 2]
    sizes = [length] * (dim - 1) + [height]
    h = [s / c for s, c in zip(sizes, counts)]
    index = {}
    nodes = []
    grid = [range(c + 1) for c in counts]
    for ijk in itertools.product(*reversed(grid)):
        ijk = tuple(reversed(ijk))
        on_min = [i == 0 for i in ijk]
        on_max = [i == c for i, c in zip(ijk, counts)]
        boundary = [a or b for a, b in zip(on_min, on_max)]
        x = [i * hh for i, hh in zip(ijk, h)]
        # a vertex on one boundary face moves within it; on two or more (an edge
        # or a corner of the block) it stays
        if sum(boundary) <= 1:
            for d in range(dim):
                if not boundary[d]:
                    x[d] += 0.2 * h[d] * rng.uniform(-1.0, 1.0)
        index[ijk] = len(nodes) + 1
        nodes.append(x + [0.0] * (3 - dim))
    elements = []

    def add(kind, tag, vertices):
        elements.append((kind, tag, vertices))

    cells = itertools.product(*[range(c) for c in counts])
    for c in cells:
        if dim == 2:
            i, j = c
            add(3, 7, [index[(i, j)], index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]])
        else:
            i, j, k = c
            bottom = [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k)]
            add(5, 7, [index[v] for v in bottom] + [index[(a, b, k + 1)] for a, b, _ in bottom])
    # boundary faces: lines (2D) or quadrilaterals (3D) with their physical tag
    for d in range(dim):
        sides = ("bottom", "top") if d == dim - 1 else (("x min", "x max") if d == 0 else ("y min", "y max"))
        others = [e for e in range(dim) if e != d]
        for side, name in zip((0, counts[d]), sides):
            for rest in itertools.product(*[range(counts[e]) for e in others]):
                def vertex(offsets):
                    ijk = [side] * dim
                    for e, r, o in zip(others, rest, offsets):
                        ijk[e] = r + o
                    return index[tuple(ijk)]
                corners = [(0,), (1,)] if dim == 2 else [(0, 0), (1, 0), (1, 1), (0, 1)]
                add(1 if dim == 2 else 3, physical[name], [vertex(c) for c in corners])
    names = ["x min", "x max", "bottom", "top"] + (["y min", "y max"] if dim == 3 else [])
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names) + 1)]
    lines += [f'{dim - 1} {physical[name]} "{name}"' for name in names] + [f'{dim} 7 "block"', "$EndPhysicalNames"]
    lines += ["$Nodes", str(len(nodes))] + [f"{i + 1} {x[0]!r} {x[1]!r} {x[2]!r}" for i, x in enumerate(nodes)]
    lines += ["$EndNodes", "$Elements", str(len(elements))]
    lines += [f"{e + 1} {kind} 2 {tag} {tag} " + " ".join(map(str, vertices))
              for e, (kind, tag, vertices) in enumerate(elements)]
    lines += ["$EndElements"]
    return "\n".join(lines) + "\n"


def scene(dim, mesh, pair, quadrature):
    """tests/scenes/distorted_block.prm for this mesh, pair and quadrature."""
    return sltest.scene(
        "distorted_block", DIM=dim, MESH=mesh, PAIR=pair, QUADRATURE=quadrature, PRESSURE=pressure,
        POINT="0, 0" if dim == 2 else "0, 0, 0", NORMAL="0, 1" if dim == 2 else "0, 0, 1",
        # in 3D the face y = 0 holds the motion along y too
        HELD_Y="y min" if dim == 3 else "x min", HELD_Y_COMPONENTS="y" if dim == 3 else "x",
        LOAD="0; -p*t" if dim == 2 else "0; 0; -p*t", VARIABLES="x,y,t" if dim == 2 else "x,y,z,t")


os.makedirs(workdir, exist_ok=True)
for dim, n in ((2, 8), (3, 4)):
    mesh = os.path.join(workdir, f"distorted_{dim}d.msh")
    with open(mesh, "w") as f:
        f.write(distorted_block(dim, n, seed=dim))
    area = length if dim == 2 else length * length
    for pair in ("Q1/P1", "Q2/P1", "Q2/P2"):
        for quadrature in ("Gauss-Lobatto", "Gauss"):
            name = f"{dim}D {pair} {quadrature}"
            out = os.path.join(workdir, f"{dim}d-{pair.replace('/', '')}-{quadrature}")
            if not sltest.run_checked(executable, scene(dim, mesh, pair, quadrature), out, check, name):
                continue
            values = [row["contact_pressure_MPa"] for row in sltest.last_profile(out + "/output")]
            error = max(abs(v - pressure) for v in values) / pressure
            check(error < 1e-10, f"{name}, distorted cells: {len(values)} contact nodes, "
                  f"max |p - {pressure}| / {pressure} = {error:.2e}")
            force = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
            force_error = abs(force - pressure * area) / (pressure * area)
            check(force_error < 1e-10, f"{name}: normal force {force:.6f} N = p x area, relative error "
                  f"{force_error:.2e}")
check.finish()
