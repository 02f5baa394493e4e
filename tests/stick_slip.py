#!/usr/bin/python3
"""Stick and slip: a block (nu = 0, so pressing alone causes no tangential
traction) is pressed by a pressure p, then its top face is pushed sideways by a
displacement d. Below the sliding load no point slips and |F_t| < mu F_n; well
above it every point in contact slips and |F_t| = mu F_n to solver tolerance.

Then a block pressed while its side x = -50 is held in x (nu = 0.3): the
corner contact node has its tangential displacement prescribed, so where it
sticks its friction multiplier is undetermined (the Dirichlet reaction carries
the friction); it is constrained to 0 there, and the run must converge to
F_n = p x length, with the forces MUMPS gives when it picks a multiplier
itself (`Linear solver/Null pivot detection`)."""
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
mu, pressure = 0.1, 100.0
for dim in (2, 3):
    # elastic shear of the block: F_t ~ G d / H * area, with G = E/2 (nu = 0)
    area = 100.0 if dim == 2 else 100.0 * 50.0
    d_slide_onset = mu * pressure * 50.0 / 100000.0
    for case, d in (("stick", 0.2 * d_slide_onset), ("slip", 10 * d_slide_onset)):
        variables = "x,y,t" if dim == 2 else "x,y,z,t"
        slide = "if(t < 0.5, 0, d*(t - 0.5)/0.5)"
        text = sltest.scene(
            "pressed_block", DIM=dim, MU=mu, SLIDE=d, NU=0.0, QUADRATURE="Gauss-Lobatto",
            SUBDIVISIONS="2, 1" if dim == 2 else "2, 1, 1", REFINEMENTS=3 if dim == 2 else 2,
            TANGENTIAL_ID=3, COMPONENTS="x" if dim == 2 else "x, y",
            SLIDE_EXPRESSION=f"{slide}; 0" if dim == 2 else f"{slide}; 0; 0",
            VARIABLES=variables, PRESSURE=pressure,
            TRACTION_EXPRESSION="0; -p*min(2*t, 1)" if dim == 2 else "0; 0; -p*min(2*t, 1)",
            STEPS=4, VTU="false")
        out = f"{workdir}/{dim}d-{case}"
        sltest.run(executable, text, out)
        s = sltest.read_csv(out + "/output/statistics.csv")[-1]
        fn, ft = s["normal_force_N"], s["tangential_force_N"]
        check(abs(fn - pressure * area) < 1e-8 * pressure * area,
              f"{dim}D {case}: normal force {fn:.6f} = p * area")
        if case == "stick":
            check(s["points_slip"] == 0 and s["points_stick"] == s["points_in_contact"] > 0,
                  f"{dim}D stick: {int(s['points_stick'])} points stick, {int(s['points_slip'])} slip")
            check(0 < ft < mu * fn, f"{dim}D stick: 0 < F_t = {ft:.4f} < mu F_n = {mu * fn:.4f}")
        else:
            check(s["points_stick"] == 0 and s["points_slip"] == s["points_in_contact"] > 0,
                  f"{dim}D slip: {int(s['points_slip'])} points slip, {int(s['points_stick'])} stick")
            check(abs(ft - mu * fn) < 1e-8 * mu * fn,
                  f"{dim}D slip: F_t = {ft:.8f} = mu F_n = {mu * fn:.8f} "
                  f"(relative difference {abs(ft - mu * fn) / (mu * fn):.1e})")
            profile = sltest.last_profile(out + "/output")
            check(all(row["status"] == 2 for row in profile),
                  f"{dim}D slip: status field is 2 (slip) at all {len(profile)} contact vertices")
text = sltest.scene(
    "pressed_block", DIM=2, MU=mu, SLIDE=0.0, NU=0.3, QUADRATURE="Gauss-Lobatto", SUBDIVISIONS="2, 1",
    REFINEMENTS=2, TANGENTIAL_ID=0, COMPONENTS="x", SLIDE_EXPRESSION="0; 0", VARIABLES="x,y,t",
    PRESSURE=pressure, TRACTION_EXPRESSION="0; -p*t", STEPS=2, VTU="false")
held = {}
for name, extra in (("held-side", ""),
                    ("held-side-null-pivots", "\nsubsection Linear solver\n  set Null pivot detection = true\nend\n")):
    code, log = sltest.run(executable, text + extra, f"{workdir}/{name}", expect_success=False)
    check(code == 0, f"{name}: exit code {code}")
    if code == 0:
        held[name] = sltest.read_csv(f"{workdir}/{name}/output/statistics.csv")[-1]
if len(held) == 2:
    fn, ft = held["held-side"]["normal_force_N"], held["held-side"]["tangential_force_N"]
    check(abs(fn - pressure * 100.0) < 1e-8 * pressure * 100.0, f"side held in x: F_n = {fn:.6f} = p x length")
    other = held["held-side-null-pivots"]
    check(abs(other["normal_force_N"] - fn) < 1e-8 * fn and abs(other["tangential_force_N"] - ft) < 1e-8 * fn,
          f"side held in x: the forces of the null-pivot solution (F_t = {ft:.6f})")
check.finish()
