#!/usr/bin/python3
"""A rigid plate free to turn (`Rigid plate <name>/Rotation = free`): a linear elastic block
on a rigid plane with friction, loaded through the plate on its top by a vertical force P
acting off centre, at the plate's reference point X_0 (tests/scenes/eccentric_plate.prm).

The plate carries the force and no moment, so the contact forces' resultant passes through
X_0 (the generalized Newton throughout, so that every run is converged to its Newton
tolerance; the nested loops' friction loop stops at 1e-4 of the threshold's change): their centroid sum x_j f_j / sum f_j is X_0's abscissa (both abscissae in 3D). The
nodal contact forces are f_j = p_j w_j with w_j = int phi_j (the Gauss-Lobatto rule these runs
use). The plate's rotation is linearised, u = U + theta x (X - X_0), and linear elasticity's
internal forces do no work on such a motion, so the balance is exact up to the Newton
tolerance (scaled residual 1e-8): checked to 1e-6 of the block's length.
- A guided plate under the same force carries the moment itself: the centroid stays at the
  centre (0 by symmetry) and the plate does not turn.
- The top face moved instead by the plate's computed motion U + theta x (X - X_0) (a Dirichlet
  condition) gives the same contact force to 1e-8: the plate's reported U and theta are its
  motion.
- 2 MPI ranks: the same forces, U and theta to 1e-8.
- Bad input: a free plate that does not tie every component is refused with a message."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
P, L, H = 100.0, 20.0, 10.0


def scene(dim, rotation, point, components=None, refinements=None):
    return sltest.scene(
        "eccentric_plate", DIM=dim, ROTATION=rotation, POINT=", ".join(repr(c) for c in point),
        SUBDIVISIONS="2, 1" if dim == 2 else "2, 2, 1", REFINEMENTS=refinements or (3 if dim == 2 else 2),
        ORIGIN="0, 0" if dim == 2 else "0, 0, 0", UP="0, 1" if dim == 2 else "0, 0, 1",
        COMPONENTS=components or ("x, y" if dim == 2 else "x, y, z"),
        FORCE=f"0; -{P}*t" if dim == 2 else f"0; 0; -{P}*t") + sltest.GENERALIZED_NEWTON


def nodal_forces(outdir, dim):
    """(position, f_j = p_j w_j) of each contact node of the last profile, w_j = int phi_j
    on the uniform grid of the bottom face."""
    profile = sltest.last_profile(outdir)
    axes = ("x_mm",) if dim == 2 else ("x_mm", "y_mm")
    coordinates = [sorted({round(row[a], 9) for row in profile}) for a in axes]

    def weight(values, v):
        i = values.index(v)
        left = values[i] - values[i - 1] if i > 0 else 0.
        right = values[i + 1] - values[i] if i + 1 < len(values) else 0.
        return 0.5 * (left + right)
    result = []
    for row in profile:
        w = 1.
        for a, values in zip(axes, coordinates):
            w *= weight(values, round(row[a], 9))
        result.append(([row[a] for a in axes], row["contact_pressure_MPa"] * w))
    return result


def centroid(forces, axis):
    return sum(x[axis] * f for x, f in forces) / sum(f for _, f in forces)


for dim, point in ((2, (3.0, H)), (3, (3.0, -2.0, H))):
    rotations = "plate_top_rotation_rad" if dim == 2 else "plate_top_rotation_y_rad"
    results = {}
    for rotation in ("free", "guided"):
        out = os.path.join(workdir, f"{dim}d-{rotation}")
        sltest.run(executable, scene(dim, rotation, point), out)
        rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
        forces = nodal_forces(os.path.join(out, "output"), dim)
        results[rotation] = (rows, forces)
        total = sum(f for _, f in forces)
        check(abs(total - P) <= 1e-8 * P and abs(rows[-1]["normal_force_N"] - P) <= 1e-8 * P,
              f"{dim}D, {rotation} plate: the contact carries P: sum p_j w_j = {total:.10g} N, "
              f"F_n = {rows[-1]['normal_force_N']:.10g} N")
        for axis in range(dim - 1):
            c = centroid(forces, axis)
            target = point[axis] if rotation == "free" else 0.
            check(abs(c - target) <= 1e-6 * L,
                  f"{dim}D, {rotation} plate: the contact forces' centroid along {'xy'[axis]} is "
                  f"{c:.9f} mm ({'X_0' if rotation == 'free' else 'the centre'}: {target} mm)")
        if rotation == "free":
            theta = [rows[-1][k] for k in rows[-1] if k.startswith("plate_top_rotation")]
            check(len(theta) == (1 if dim == 2 else 3) and abs(rows[-1][rotations]) > 1e-4,
                  f"{dim}D, free plate: statistics.csv has its rotation, {theta} rad")
        else:
            check(not any(k.startswith("plate_top_rotation") for k in rows[-1]),
                  f"{dim}D, guided plate: no rotation column")
    # the guided plate's contact is centred, the free one's is not: the test tells them apart
    check(abs(centroid(results["guided"][1], 0) - centroid(results["free"][1], 0)) > 0.1 * point[0],
          f"{dim}D: the free plate moves the contact's centroid by "
          f"{centroid(results['free'][1], 0) - centroid(results['guided'][1], 0):.3f} mm")

    if dim == 2:
        rows = results["free"][0]
        last = rows[-1]
        x0, y0 = point

        def path(key):
            """The plate's value of `key`, linear between the step times (friction makes the
            response depend on the path, so the moved face follows the plate's steps)."""
            (t1, v1), (t2, v2) = [(row["time"], row[key]) for row in rows]
            return f"if(t <= {t1!r}, {v1!r}*t/{t1!r}, {v1!r} + ({v2!r} - {v1!r})*(t - {t1!r})/({t2!r} - {t1!r}))"
        ux, uy, theta = (path("plate_top_displacement_x_mm"), path("plate_top_displacement_y_mm"),
                         path("plate_top_rotation_rad"))
        moved = scene(2, "free", point).replace(
            "  subsection Rigid plate top\n", "  subsection Dirichlet top\n").replace(
            "    set Components      = x, y\n    set Rotation        = free\n", "    set Components = x, y\n").replace(
            f"    set Reference point = {x0!r}, {y0!r}\n", "").replace(
            "    subsection Force\n", "    subsection Displacement\n").replace(
            f"set Function expression = 0; -{P}*t",
            f"set Function expression = {ux} - ({theta})*(y - {y0!r}); {uy} + ({theta})*(x - {x0!r})")
        check("Dirichlet top" in moved and "Rigid plate" not in moved and "Reference point" not in moved,
              "the moved scene holds the top face by a Dirichlet condition")
        out = os.path.join(workdir, "2d-moved")
        sltest.run(executable, moved, out)
        force = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]["normal_force_N"]
        check(abs(force - P) <= 1e-8 * P,
              f"2D: the top face moved by the plate's U = ({last['plate_top_displacement_x_mm']:.6f}, "
              f"{last['plate_top_displacement_y_mm']:.6f}) mm, theta = {last['plate_top_rotation_rad']:.3e} "
              "rad instead: "
              f"F_n = {force:.10g} N = P")

        out = os.path.join(workdir, "2d-free-2ranks")
        sltest.run(executable, scene(2, "free", point), out, ranks=2)
        two = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))[-1]
        keys = ("normal_force_N", "tangential_force_N", "plate_top_displacement_x_mm",
                "plate_top_displacement_y_mm", "plate_top_rotation_rad")
        # (the tangential force is round-off, 1e-13 N: forces are compared against P)
        worst = max(abs(two[k] - last[k]) / (P if k.endswith("_N") else abs(last[k])) for k in keys)
        check(worst <= 1e-8, f"2D, 2 ranks: forces, U and theta as on 1 rank (largest relative "
              f"difference {worst:.1e})")

code, log = sltest.run(executable, scene(2, "free", (3.0, H), components="y"), os.path.join(workdir, "bad"),
                       expect_success=False)
check(code != 0 and "Rotation = free" in log and "Components = x, y" in log,
      "a free plate tying only y is refused, naming the entry and what to set")
check.finish()
