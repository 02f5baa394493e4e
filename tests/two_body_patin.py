#!/usr/bin/python3
"""The elastic patin on a deformable lower block (prm/patin_deformable_block.prm)
tends to the patin on the rigid obstacle (prm/gmsh_block.prm, the same mesh of
the patin) as the lower block stiffens.

With the lower block's Young's modulus E_2 = k E (k = 1, 1e2, 1e4): its
displacements scale as 1/k, the master surface tends to the plane y = 0 and
the discrete problem of the patin to the rigid obstacle's (same slave nodes,
same contact quadrature, a flat master surface paired with the slave points
as the plane is), at first order in 1/k. Checked on the final load step (the
patin pressed by 0.5 mm and slid by 0.5 mm): the normal and tangential forces
(statistics.csv) and the nodal contact pressure of the patin's bottom
(profile, the same nodes) differ from the rigid result by amounts that
decrease strictly with k, and by less than 1% at k = 1e4, where the first
order estimate is ~1e-4 times the k = 1 difference. The rigid reference is
run with the contact quadrature of the two-body scene (Gauss) and its conditions
(the weighted ones, which `Complementarity = automatic` takes for two bodies and
not for a rigid obstacle: set on the rigid run). Checked with the
scene's r_n = automatic (which the stiffest body sets, so that it grows with k)
and with r_n fixed at its k = 1 value.

Also: 1 and 2 MPI ranks give the same forces at every load step, relative
1e-8 of the normal force (the Newton tolerance), for k = 1."""
import os
import re
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm"))
two_body = sltest.read_prm(os.path.join(prm_dir, "patin_deformable_block.prm"))
rigid = sltest.read_prm(os.path.join(prm_dir, "gmsh_block.prm"))
E = 200000.0

quadrature = re.compile(r"set Contact quadrature\s*=\s*\S+")
rigid = (quadrature.sub("set Contact quadrature   = Gauss", rigid) +
         sltest.nested_set("Contact/Complementarity", "weighted"))
check("Gauss-Lobatto" not in rigid and bool(re.search(r"set Contact quadrature\s*=\s*Gauss\n", two_body)),
      "the rigid reference and the two-body scene use the Gauss contact quadrature")
head, material_2, tail = re.split(r"(subsection Material 2\n.*?\nend\n)", two_body, maxsplit=1, flags=re.S)
modulus = re.compile(r"set Young's modulus = \S+")
check(len(modulus.findall(material_2)) == 1 and "set Bodies = lower" in material_2,
      "the scene gives the lower block its own Young's modulus (Material 2, Bodies = lower)")


def with_stiffness(k):
    return head + modulus.sub(f"set Young's modulus = {k * E:g}", material_2) + tail


def run(name, text, ranks=1):
    """Statistics rows and last profile of a run, or None if it failed."""
    out = os.path.join(workdir, name)
    if not sltest.run_checked(executable, text, out, check, name, ranks=ranks):
        return None
    return (sltest.read_csv(os.path.join(out, "output", "statistics.csv")),
            sltest.last_profile(os.path.join(out, "output")))


reference = run("rigid", rigid)
stiffnesses = (1, 100, 10000)
runs = {k: run(f"k{k:g}", with_stiffness(k)) for k in stiffnesses}
if reference is None or any(r is None for r in runs.values()):
    check.finish()
rigid_stats, rigid_profile = reference
Fn0, Ft0 = rigid_stats[-1]["normal_force_N"], rigid_stats[-1]["tangential_force_N"]
p_rigid = {(round(r["x_mm"], 6), round(r["y_mm"], 6)): r["contact_pressure_MPa"] for r in rigid_profile}
p_scale = max(p_rigid.values())
print(f"rigid obstacle: F_n = {Fn0:.3f} N/mm, F_t = {Ft0:.3f} N/mm, max pressure {p_scale:.3f} MPa")


def convergence(label, runs):
    """Check that the runs of increasing stiffness tend to the rigid obstacle's."""
    differences = {"normal force": [], "tangential force": [], "pressure profile": []}
    for k in stiffnesses:
        stats, profile = runs[k]
        check(len(stats) == len(rigid_stats) and abs(stats[-1]["time"] - 1) < 1e-12,
              f"{label}, k = {k:g}: the load path completed")
        Fn, Ft = stats[-1]["normal_force_N"], stats[-1]["tangential_force_N"]
        p = {(round(r["x_mm"], 6), round(r["y_mm"], 6)): r["contact_pressure_MPa"] for r in profile}
        check(set(p) == set(p_rigid), f"{label}, k = {k:g}: the profile has the rigid run's {len(p_rigid)} "
              "slave nodes")
        profile_difference = (max(abs(p[x] - p_rigid[x]) for x in p_rigid) / p_scale
                              if set(p) == set(p_rigid) else float("inf"))
        differences["normal force"].append(abs(Fn - Fn0) / Fn0)
        differences["tangential force"].append(abs(Ft - Ft0) / Ft0)
        differences["pressure profile"].append(profile_difference)
        print(f"{label}, k = {k:g}: F_n = {Fn:.3f}, F_t = {Ft:.3f} N/mm; relative differences to the rigid "
              f"obstacle: F_n {differences['normal force'][-1]:.3e}, "
              f"F_t {differences['tangential force'][-1]:.3e}, "
              f"pressure (max over the nodes / max pressure) {profile_difference:.3e}")
    for what, values in differences.items():
        text = " > ".join(f"{v:.2e}" for v in values)
        check(all(b < a for a, b in zip(values, values[1:])),
              f"{label}, {what}: the difference to the rigid obstacle decreases as the block stiffens ({text})")
        check(values[-1] < 0.01, f"{label}, {what}: {values[-1]:.2e} < 1% at k = {stiffnesses[-1]:g}")


# the scene as it is: r_n = automatic (set by the stiffest body, so it grows with k)
convergence("r_n automatic", runs)
# the same with r_n fixed at its automatic value for k = 1 (E/h of the patin):
# the discrete problem then depends on k only through the lower block, and its
# limit is the rigid obstacle's discrete problem
r_n = sltest.read_csv(os.path.join(workdir, "k1", "output", "run_summary.csv"))[0]["r_n"]
automatic = re.compile(r"set r_n\s*=\s*automatic")
check(len(automatic.findall(two_body)) == 1, "the scene has r_n = automatic")
fixed = {k: run(f"k{k:g}-fixed-r_n", automatic.sub(f"set r_n = {r_n:g}", with_stiffness(k))) for k in stiffnesses}
if all(r is not None for r in fixed.values()):
    convergence(f"r_n = {r_n:g}", fixed)

# 1 and 2 ranks, k = 1
two_ranks = run("k1-np2", with_stiffness(1), ranks=2)
if two_ranks is not None:
    one, two = runs[1][0], two_ranks[0]
    check(len(one) == len(two), f"1 and 2 ranks: {len(one)} and {len(two)} load steps")
    worst = max(abs(a[f] - b[f]) / abs(a["normal_force_N"]) for a, b in zip(one, two)
                for f in ("normal_force_N", "tangential_force_N", "contact_force_x_N", "contact_force_y_N"))
    check(worst < 1e-8, f"1 and 2 ranks: the same forces at every step (max difference {worst:.1e} of F_n)")
check.finish()
