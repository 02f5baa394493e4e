#!/usr/bin/python3
"""The Hertz scenes with a given pair and mesh, and the errors of a computed
contact pressure profile against Hertz's closed form with the run's own
normal force P (shared by contrib/benchmark_hertz.py and tests/hertz_pairs.py).

Plane strain (dim = 2): a = sqrt(4PR/(pi E*)), p0 = 2P/(pi a); sphere (dim = 3):
a = (3PR/(4E*))^(1/3), p0 = 3P/(2 pi a^2); p(r) = p0 sqrt(1 - r^2/a^2).
The profile has a row per node of the contact faces (vertices, and midsides
for quadratic pairs). Half-width: midpoint between the last loaded and the
first unloaded node. Peak: the largest nodal pressure. L2 (2D): the nodal
values interpolated linearly along x against the exact curve, 40 samples per
interval, so the square-root edge is integrated accurately; 3D: root mean
square of the nodal errors over the nodes within 1.5 a. Surface L2
(surface_l2_error): in 2D the L2 error above; in 3D the L2 integral within
1.5 a of the nodal values interpolated linearly on the Delaunay triangles of
the nodes (the nodal root mean square weighs the nodes of a graded mesh by
their number, not their area, and leaves out the error between them). Fitted
half-width (fitted_half_width_error): the a of the least-squares fit of
q sqrt(1 - r^2/a^2) to every node, q and a free (golden-section search in a,
q linear), which uses the whole profile rather than the two nodes around the
edge, so it is not bounded below by h/2."""
import math
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def hertz_scene(dim, pair, local_refinements, delta):
    """The text of prm/hertz_cylinder.prm (dim 2) or prm/hertz_sphere.prm (dim 3)
    with the FE pair, the local refinements of the contact zone, the
    indentation delta, and the whole load in one step."""
    name = "hertz_cylinder" if dim == 2 else "hertz_sphere"
    with open(os.path.join(ROOT, "prm", name + ".prm")) as f:
        text = f.read()
    default_local = "4" if dim == 2 else "3"
    text = text.replace(f"set Local refinements       = {default_local}",
                        f"set Local refinements       = {local_refinements}")
    return text + f"""
subsection Contact
  set Finite element pair = {pair}
end
subsection Boundary conditions
  subsection Dirichlet 1
    subsection Displacement
      set Function constants = delta={delta}
    end
  end
end
subsection Load stepping
  set Number of load steps = 1
end
"""


def hertz_errors(dim, P, profile, E=200000.0, nu=0.3, R=100.0):
    """Errors of a profile (rows of profile-NNNNN.csv) of a run with normal force P."""
    E_star = E / (1 - nu * nu)
    if dim == 2:
        a_h = math.sqrt(4 * P * R / (math.pi * E_star))
        p0_h = 2 * P / (math.pi * a_h)
        pts = [(row["x_mm"], row["contact_pressure_MPa"]) for row in profile]
    else:
        a_h = (3 * P * R / (4 * E_star)) ** (1 / 3)
        p0_h = 3 * P / (2 * math.pi * a_h ** 2)
        pts = sorted((math.hypot(row["x_mm"], row["y_mm"]), row["contact_pressure_MPa"]) for row in profile)

    def exact(x):
        return p0_h * math.sqrt(max(0.0, 1 - (x / a_h) ** 2))
    loaded = [x for x, p in pts if p > 0]
    reach = max(abs(x) for x in loaded)
    beyond = min((abs(x) for x, p in pts if p <= 0 and abs(x) > reach), default=reach)
    a = 0.5 * (reach + beyond)
    h = beyond - reach
    p0 = max(p for _, p in pts)
    if dim == 2:
        # the computed profile interpolated linearly between the vertices,
        # against the exact curve, with 40 midpoint samples per interval (the
        # square-root edge of the exact curve is integrated accurately)
        num = den = 0.0
        for (x0, p0_), (x1, p1_) in zip(pts, pts[1:]):
            dx = (x1 - x0) / 40
            for k in range(40):
                t = (k + 0.5) / 40
                x = x0 + t * (x1 - x0)
                num += dx * ((1 - t) * p0_ + t * p1_ - exact(x)) ** 2
                den += dx * exact(x) ** 2
    else:
        near = [(x, p) for x, p in pts if x <= 1.5 * a_h]
        num = sum((p - exact(x)) ** 2 for x, p in near)
        den = sum(exact(x) ** 2 for x, _ in near)
    surface = math.sqrt(num / den) if dim == 2 else surface_l2_error(profile, exact, 1.5 * a_h)
    a_fit = fitted_half_width(pts, a_h)
    return {"h_mm": h, "half_width_error": abs(a - a_h) / a_h, "peak_error": abs(p0 - p0_h) / p0_h,
            "l2_error": math.sqrt(num / den), "surface_l2_error": surface, "a_mm": a, "a_hertz_mm": a_h,
            "fitted_half_width_error": abs(a_fit - a_h) / a_h, "a_fit_mm": a_fit}


def fitted_half_width(pts, a_guess):
    """The a of the least-squares fit of q sqrt(1 - r^2/a^2) to the (r, p) of pts, q and a free."""
    def misfit(a):
        shape = [math.sqrt(max(0.0, 1 - (r / a) ** 2)) for r, _ in pts]
        norm = sum(f * f for f in shape)
        q = sum(f * p for f, (_, p) in zip(shape, pts)) / norm if norm > 0 else 0.0
        return sum((q * f - p) ** 2 for f, (_, p) in zip(shape, pts))
    low, high = 0.5 * a_guess, 1.5 * a_guess
    ratio = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        left, right = high - ratio * (high - low), low + ratio * (high - low)
        if misfit(left) < misfit(right):
            high = right
        else:
            low = left
    return 0.5 * (low + high)


def surface_l2_error(profile, exact, radius):
    """3D: the relative L2 error on the contact surface within radius of the
    axis, the nodal pressures interpolated linearly on the Delaunay triangles
    of the nodes' (x, y) (the surface is nearly flat where a << R), 15
    samples per side of each triangle (the square-root edge integrated
    accurately)."""
    import matplotlib.tri
    x = [row["x_mm"] for row in profile]
    y = [row["y_mm"] for row in profile]
    p = [row["contact_pressure_MPa"] for row in profile]
    n = 15
    samples = [(i / n + 1 / (3 * n), j / n + 1 / (3 * n)) for i in range(n) for j in range(n - i)]
    samples += [(i / n + 2 / (3 * n), j / n + 2 / (3 * n)) for i in range(n) for j in range(n - i - 1)]
    num = den = 0.0
    for a, b, c in matplotlib.tri.Triangulation(x, y).triangles:
        if min(math.hypot(x[v], y[v]) for v in (a, b, c)) > radius:
            continue
        area = 0.5 * abs((x[b] - x[a]) * (y[c] - y[a]) - (x[c] - x[a]) * (y[b] - y[a]))
        for s, t in samples:
            sx = x[a] + s * (x[b] - x[a]) + t * (x[c] - x[a])
            sy = y[a] + s * (y[b] - y[a]) + t * (y[c] - y[a])
            computed = p[a] + s * (p[b] - p[a]) + t * (p[c] - p[a])
            reference = exact(math.hypot(sx, sy))
            num += area * (computed - reference) ** 2
            den += area * reference ** 2
    return math.sqrt(num / den)


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import tool_cli
    tool_cli.module_help(__doc__)
