#!/usr/bin/python3
"""Large rotation: a neo-Hookean block turned by a large angle as a rigid body,
then pressed onto and slid along a plane turned by the same angle, gives the
contact force of the unrotated problem, rotated (tests/scenes/rotated_block.prm).

The two discrete problems are the same up to a rotation of the deformed
configuration (objective material, gap and pairing evaluated in the deformed
configuration, Dirichlet data interpolated exactly at the nodes), so the
forces agree up to the Newton tolerance (1e-6 N on forces of ~100 N): the
tolerance is 1e-6 relative. A small-strain model fails this test: with
theta = 1.5 the linearised strain of the rigid rotation alone is of order 1
(linear elasticity in this scene: the turned block already presses on the
plane before phase 2 and the forces differ by more than 100 %)."""
import math
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()


def run(theta, material="neo-Hookean"):
    D = 11.0  # more than the half-length: the turning contact face stays clear of the plane
    normal = f"{-math.sin(theta)!r}, {math.cos(theta)!r}"
    point = f"{D * math.sin(theta)!r}, {-D * math.cos(theta)!r}"
    text = sltest.scene("rotated_block", THETA=repr(theta), NORMAL=normal, POINT=point, D=D, REFINEMENTS=2,
                        STEPS=24, MATERIAL=material)
    out = f"{workdir}/theta-{theta}-{material.replace(' ', '_')}"
    code, log = sltest.run(executable, text, out, expect_success=False)
    if code != 0:
        print(log[-3000:])
    return code, (sltest.read_csv(out + "/output/statistics.csv") if code == 0 else [])


theta = 1.5
code0, reference = run(0.0)
code1, rotated = run(theta)
check(code0 == 0 and code1 == 0, f"both runs converge (exit codes {code0}, {code1})")
if code0 == 0 and code1 == 0:
    check(len(reference) == len(rotated), f"same number of load steps ({len(reference)}, {len(rotated)})")
    c, s = math.cos(theta), math.sin(theta)
    for r0, r1 in zip(reference, rotated):
        if r0["time"] <= 1.0 + 1e-12:
            continue  # phase 1: no contact yet
        scale = max(abs(r0["normal_force_N"]), 1.0)
        fx = c * r0["contact_force_x_N"] - s * r0["contact_force_y_N"]
        fy = s * r0["contact_force_x_N"] + c * r0["contact_force_y_N"]
        error = max(abs(r1["normal_force_N"] - r0["normal_force_N"]),
                    abs(r1["tangential_force_N"] - r0["tangential_force_N"]),
                    abs(r1["contact_force_x_N"] - fx), abs(r1["contact_force_y_N"] - fy)) / scale
        check(error < 1e-6, f"t = {r0['time']:.3f}: normal force {r1['normal_force_N']:.6f} N "
              f"(unrotated {r0['normal_force_N']:.6f} N), tangential {r1['tangential_force_N']:.6f} N "
              f"(unrotated {r0['tangential_force_N']:.6f} N): relative difference {error:.2e}")
    last = reference[-1]
    check(last["normal_force_N"] > 0 and last["tangential_force_N"] > 0,
          f"the final state is pressed ({last['normal_force_N']:.3f} N) and sheared "
          f"({last['tangential_force_N']:.3f} N)")
check.finish()
