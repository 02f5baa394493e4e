#!/usr/bin/python3
"""A block pressed uniformly onto a frictionless rigid plane: the contact pressure
is uniform and equal to the applied pressure, to solver tolerance, for every
inf-sup stable pair (Q1/P1, Q2/P1, Q2/P2, Q1/P1 coarse) and both contact
quadratures, also with hanging nodes across the contact surface (3D; not for
the coarse pair, which refuses them with a message), and
for Q1/P0 in 2D (unstable, but a constant pressure is in its space and its
system is invertible); the exact solution is linear, so every pair represents
it exactly. Q1/P2 is singular and left out."""
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
pressure = 100.0
pairs = ("Q1/P1", "Q2/P1", "Q2/P2", "Q1/P1 coarse", "Q1/P0")
cases = [(dim, pair, quadrature, local) for dim in (2, 3) for pair in pairs
         for quadrature in ("Gauss-Lobatto", "Gauss") for local in (0, 1)
         if not (dim == 3 and pair == "Q1/P0") and not (dim == 3 and local and pair == "Q1/P1 coarse")]
for dim, pair, quadrature, local in cases:
    if True:
        # local = 1: the cells within 30 mm of the corner (-50, 0(, 0)) refined once
        # more, so hanging nodes run across the contact surface
        center = "-50, 0" if dim == 2 else "-50, 0, 0"
        variables = "x,y,t" if dim == 2 else "x,y,z,t"
        text = sltest.scene(
            "pressed_block", DIM=dim, MU=0, SLIDE=0, NU=0.3, QUADRATURE=quadrature,
            SUBDIVISIONS="2, 1" if dim == 2 else "2, 1, 1", REFINEMENTS=3 if dim == 2 else 2,
            TANGENTIAL_ID=0, COMPONENTS="x", SLIDE_EXPRESSION="0; 0" if dim == 2 else "0; 0; 0",
            VARIABLES=variables, PRESSURE=pressure, PAIR=pair, LOCAL=local, CENTER=center, RADIUS=30,
            TRACTION_EXPRESSION="0; -p*t" if dim == 2 else "0; 0; -p*t", STEPS=2, VTU="false")
        name = f"{dim}D {pair} {quadrature}" + (" locally refined" if local else "")
        out = f"{workdir}/{dim}d-{pair.replace('/', '').replace(' ', '_')}-{quadrature}-{local}"
        sltest.run(executable, text, out)
        profile = sltest.last_profile(out + "/output")
        values = [row["contact_pressure_MPa"] for row in profile]
        error = max(abs(v - pressure) for v in values) / pressure
        check(error < 1e-8, f"{name}: {len(values)} vertices, "
              f"max |p - {pressure}| / {pressure} = {error:.2e}")
        stats = sltest.read_csv(out + "/output/statistics.csv")[-1]
        area = 100.0 if dim == 2 else 100.0 * 50.0
        force_error = abs(stats["normal_force_N"] - pressure * area) / (pressure * area)
        check(force_error < 1e-8, f"{name}: normal force {stats['normal_force_N']:.6f}"
              f" = p * area, relative error {force_error:.2e}")
check.finish()
