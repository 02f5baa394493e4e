#!/usr/bin/python3
"""Every FE pair solves the frictionless Hertz cylinder (prm/hertz_cylinder.prm,
indentation 0.25 mm, the whole load in one step from rest), with a relative
L2 error of the pressure profile that decreases at each of three meshes (the
contact zone refined uniformly) at a rate consistent with the pair:

- the exact pressure has a square-root edge, which limits every stable pair
  to about first order in L2 whatever its degree (measured: 0.8-1.5 between
  the first and the last mesh); the check asks for at least 0.6;
- Q1/P0 violates the inf-sup condition: it still converges in this measure
  (its profile holds, at each vertex, the value of one of the two faces
  that share it), but slower and with an error at least twice that of
  Q1/P1 on the same mesh.

The L2 error: the nodal values interpolated linearly along x against the
closed form with the run's own force, integrated with 40 samples per interval
(contrib/hertz_errors.py, shared with the benchmark)."""
import math
import os
import sys
import sltest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "contrib"))
from hertz_errors import hertz_errors, hertz_scene  # noqa: E402

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()


def l2_error(pair, local):
    text = hertz_scene(2, pair, local, 0.25)
    out = f"{workdir}/{pair.replace('/', '').replace(' ', '_')}-{local}"
    if not sltest.run_checked(executable, text, out, check, f"{pair} local {local}"):
        return None
    P = sltest.read_csv(out + "/output/statistics.csv")[-1]["normal_force_N"]
    return hertz_errors(2, P, sltest.last_profile(out + "/output"))["l2_error"]


meshes = {"Q1/P1": (4, 5, 6), "Q1/P1 coarse": (4, 5, 6), "Q2/P1": (3, 4, 5), "Q2/P2": (3, 4, 5),
          "Q1/P0": (3, 4, 5)}
errors = {}
for pair, levels in meshes.items():
    e = [l2_error(pair, local) for local in levels]
    if None in e:
        continue
    errors[pair] = dict(zip(levels, e))
    order = math.log(e[0] / e[-1]) / math.log(2 ** (levels[-1] - levels[0]))
    minimum = 0.3 if pair == "Q1/P0" else 0.6
    check(e[0] > e[1] > e[2] and order >= minimum,
          f"{pair}: L2 errors {', '.join(f'{x:.2%}' for x in e)} (h halved each time), "
          f"order {order:.2f} >= {minimum}")
if "Q1/P0" in errors and "Q1/P1" in errors:
    check(errors["Q1/P0"][5] > 2 * errors["Q1/P1"][5],
          f"Q1/P0 (unstable) is less accurate than Q1/P1 on the same mesh: "
          f"{errors['Q1/P0'][5]:.2%} vs {errors['Q1/P1'][5]:.2%}")
check.finish()
