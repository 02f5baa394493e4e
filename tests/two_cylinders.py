#!/usr/bin/python3
"""Two equal elastic cylinders (prm/two_cylinders.prm, plane strain, R = 50 mm,
E = 200000 MPa, nu = 0.3, mu = 0.2), two deformable bodies with non-matching
meshes on the contact zone.

After the normal phase (the upper flat top moved down, t = 0.5): Hertz for two
equal cylinders, R* = R/2, E* = E / (2 (1 - nu^2)),
b = sqrt(4 P R* / (pi E*)), p0 = 2 P / (pi b), with P the computed normal
force. After the tangential phase (the top moved sideways, t = 1):
Cattaneo-Mindlin, Q < mu P and a central stick zone of half-width
c = b sqrt(1 - Q / (mu P)) (equal materials: the normal and tangential
problems uncouple, Dundurs beta = 0).

Half-widths are estimated as in tests/hertz.py: midway between the last node
inside (loaded, resp. sticking) and the first node outside, on the slave
surface (the upper cylinder, reference coordinates)."""
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
scene = sltest.read_prm(os.path.join(prm_dir, "two_cylinders.prm"))
E, nu, R, mu = 200000.0, 0.3, 50.0, 0.2
R_star, E_star = R / 2, E / (2 * (1 - nu * nu))
for entry in (f"set Young's modulus = {E:.0f}", f"set Poisson's ratio = {nu}",
              f"set Friction coefficient = {mu}"):
    if entry not in scene:
        raise SystemExit(f"FAIL: prm/two_cylinders.prm has no '{entry}'")


def half_width(profile, inside):
    """Midpoint estimate of the half-width of the zone of nodes satisfying `inside`
    around the node nearest x = 0, and the node spacing h at its two ends."""
    xs = [row["x_mm"] for row in profile]
    centre = min(range(len(xs)), key=lambda i: abs(xs[i]))
    if not inside(profile[centre]):
        return None, None
    left = right = centre
    while left > 0 and inside(profile[left - 1]):
        left -= 1
    while right < len(xs) - 1 and inside(profile[right + 1]):
        right += 1
    if left == 0 or right == len(xs) - 1:
        return None, None
    width = 0.25 * ((xs[right] + xs[right + 1]) - (xs[left] + xs[left - 1]))
    h = max(xs[right + 1] - xs[right], xs[left] - xs[left - 1])
    return width, h


out = os.path.join(workdir, "run")
code, log = sltest.run(executable, scene + sltest.QUIET_OUTPUT, out, expect_success=False)
check(code == 0, f"exit code {code}")
if code != 0:
    print(log[-3000:])
    check.finish()
stats = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))


def profile_of(row):
    return sltest.read_csv(os.path.join(out, "output", f"profile-{int(row['step']):05d}.csv"))


# --- normal phase: Hertz --------------------------------------------------------
normal = min(stats, key=lambda row: abs(row["time"] - 0.5))
check(abs(normal["time"] - 0.5) < 1e-12, f"a load step ends the normal phase (t = {normal['time']})")
P = normal["normal_force_N"]
profile = profile_of(normal)
b, h = half_width(profile, lambda row: row["contact_pressure_MPa"] > 0)
b_hertz = math.sqrt(4 * P * R_star / (math.pi * E_star))
p0_hertz = 2 * P / (math.pi * b_hertz)
p0 = max(row["contact_pressure_MPa"] for row in profile)
print(f"normal phase: P = {P:.1f} N/mm, b = {b} (Hertz {b_hertz:.4f}) mm, h = {h} mm, "
      f"p0 = {p0:.1f} (Hertz {p0_hertz:.1f}) MPa")
check(b is not None, "normal phase: a contact zone around x = 0, open nodes on both sides")
if b is not None:
    check(b_hertz >= 10 * h, f"normal phase: the contact half-width holds {b_hertz / h:.1f} >= 10 cells")
    # The midpoint estimate is within h/2 of the discrete contact edge (sampled at
    # the slave nodes), and the discrete edge lies within the cell around the
    # exact one, h/2 more: |b - b_H| <= h. The model error of the closed form
    # (half-spaces against finite half discs) is O((b/R)^2) ~ 0.4% of b, far below h.
    check(abs(b - b_hertz) <= h, f"normal phase: |b - b_H| = {abs(b - b_hertz):.4f} mm <= h = {h:.4f} mm")
# The peak is sampled at the slave node at x = 0, the centre of the zone, where
# the pressure is smooth: the error of the P1 multiplier there is O((h/b)^2),
# about 0.6% with b/h ~ 12, and the closed form's model error O((b/R)^2) about
# 0.4%; 2% bounds their sum with a margin of 2 for the constants.
p0_error = abs(p0 - p0_hertz) / p0_hertz
check(p0_error <= 0.02, f"normal phase: peak pressure error {p0_error:.2%} <= 2%")

# --- tangential phase: Cattaneo-Mindlin ------------------------------------------
last = stats[-1]
check(abs(last["time"] - 1) < 1e-12, f"the run reaches t = 1 (t = {last['time']})")
P_last, Q = last["normal_force_N"], last["tangential_force_N"]
ratio = Q / (mu * P_last)
print(f"tangential phase: P = {P_last:.1f} N/mm ({(P_last - P) / P:+.3%} against the normal phase), "
      f"Q = {Q:.2f} N/mm, Q / (mu P) = {ratio:.4f}")
check(Q > 0 and ratio < 1, f"tangential phase: 0 < Q = {Q:.2f} < mu P = {mu * P_last:.2f} N/mm")
profile = profile_of(last)
statuses = [int(row["status"]) for row in profile]
check(2 in statuses, f"tangential phase: slipping nodes at the edges of the contact zone "
      f"({statuses.count(1)} stick, {statuses.count(2)} slip)")
c, h_c = half_width(profile, lambda row: row["status"] == 1)
b_last = math.sqrt(4 * P_last * R_star / (math.pi * E_star))
c_mindlin = b_last * math.sqrt(max(0.0, 1 - ratio))
print(f"tangential phase: stick zone half-width c = {c} (Cattaneo-Mindlin {c_mindlin:.4f}) mm, "
      f"h = {h_c} mm, contact half-width b_H = {b_last:.4f} mm")
check(c is not None, "tangential phase: a stick zone around x = 0, slip on both sides")
if c is not None:
    # The scene must load the contact so that the stick zone is measurably
    # smaller than the contact zone: b - c above the tolerance below.
    check(b_last - c_mindlin > 2 * h_c, f"tangential phase: b - c_CM = {b_last - c_mindlin:.3f} mm > 2 h "
          "(the stick zone is resolved apart from the contact zone)")
    # As for b: h/2 for sampling the stick/slip boundary at the slave nodes, h/2
    # for the position of the discrete boundary (the statuses are decided node by
    # node from multipliers with an O(h) error at the kink of the tangential
    # traction at |x| = c).
    check(abs(c - c_mindlin) <= h_c, f"tangential phase: |c - c_CM| = {abs(c - c_mindlin):.4f} mm "
          f"<= h = {h_c:.4f} mm")
check.finish()
