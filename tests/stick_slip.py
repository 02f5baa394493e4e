#!/usr/bin/python3
"""Stick and slip: a block (nu = 0, so pressing alone causes no tangential
traction) is pressed by a pressure p, then its top face is pushed sideways by a
displacement d. Below the sliding load no point slips and |F_t| < mu F_n; well
above it every point in contact slips and |F_t| = mu F_n to solver tolerance.

Then a block pressed while its side x = -50 is held in x (nu = 0.3): the
corner contact node has its tangential displacement prescribed, so where it
sticks its friction multiplier is undetermined and the Newton system singular.
The run must end cleanly (exit 2) with a message that names the cause and
`Linear solver/Null pivot detection`; with that entry on, it converges to
F_n = p x length."""
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
code, log = sltest.run(executable, text, f"{workdir}/held-side", expect_success=False)
check(code == 2 and "tangential displacement is prescribed" in log and "Null pivot detection" in log,
      f"side held in x: exit code {code}, the message names the cause and the remedy")
out = f"{workdir}/held-side-null-pivots"
sltest.run(executable, text + "\nsubsection Linear solver\n  set Null pivot detection = true\nend\n", out)
fn = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
check(abs(fn - pressure * 100.0) < 1e-8 * pressure * 100.0,
      f"side held in x, null pivot detection: F_n = {fn:.6f} = p x length")
check.finish()
